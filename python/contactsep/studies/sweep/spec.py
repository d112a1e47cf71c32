"""Parameter sweeps and tolerance studies, in chunks.

A sweep is the thesis design with some fields varied over lists or ranges
(several form a grid) and/or sampled from distributions (a tolerance
study); design i of the sweep is grid point i // K, sample i % K.  Each
design is evaluated by a model: ``eq23`` (the general model, a chunk in
one compiled batch), or ``hertz`` or ``newton`` (the three-beam chatter
simulation, contactsep.studies.sweep.chatter, which may also vary the
simulation's settings preload, min_open and damping).  Chunks are
evaluated in this process, in a process pool on the local cores, or on
a Dask cluster, and streamed in order to the output: memory is bounded
by a few chunks whatever the size.  What --vary and --sample take is
parsed in :mod:`contactsep.studies.sweep.axes`.

Samples are reproducible and independent of the chunking: sample k of a
field is drawn from block k // SAMPLE_BLOCK of a generator seeded with
(seed, field index, block), so local and Dask runs give identical bits.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from contactsep.model import evaluate, thesis_design
from contactsep.model.design import Design
from contactsep.model.names import shown_data
from contactsep.model import fields as design_fields
from contactsep.model.fields import column_name
from contactsep.studies.stats import RunningMoments, wilson_interval
from contactsep.studies.sweep.checks import (
    SweepError,
    check_chatter_modes,
    check_dt,
    check_fixed,
    check_model,
    check_preload,
    check_elastic,
    check_used,
)
from contactsep.studies.sweep.axes import (
    MAX_DESIGNS,
    LinearAxis,
    parse_sample,
    parse_vary,
)

#: Samples drawn per generator block (fixes the stream, not the chunking).
SAMPLE_BLOCK = 65536
#: Default designs per chunk, and the most a chunk may have (the
#: columns of a million designs are ~0.5 GB in the parent).
CHUNK_SIZE = 100_000
MAX_CHUNK_SIZE = 1_000_000
#: Output columns beside the varied fields.
RESULT_COLUMNS = ("y3_max_in", "t_max_s", "psi_lb_s", "v0_in_s", "status")


@dataclass(frozen=True)
class SweepSpec:
    """What a sweep evaluates (picklable: it travels to workers)."""

    #: Design fields fixed for every design (thesis_design overrides).
    base: dict = field(default_factory=dict)
    #: (name, values) of each varied field, in grid order (last fastest).
    vary: tuple = ()
    #: (name, kind, a, b) of each sampled field.
    sample: tuple = ()
    #: Samples per grid point (1 without --sample).
    samples: int = 1
    seed: int = 0
    backend: str = "compiled"
    #: "eq23" (the general model) or a chatter model ("hertz", "newton").
    model: str = "eq23"
    #: Chatter settings fixed for every design (preload, min_open,
    #: damping; the rest take simulate()'s defaults).
    settings: dict = field(default_factory=dict)

    @property
    def grid_shape(self) -> tuple:
        return tuple(len(values) for _, values in self.vary)

    @property
    def size(self) -> int:
        """Number of designs."""
        return math.prod(self.grid_shape) * self.samples

    @property
    def max_modes(self) -> int:
        """The largest N of any member of any design (chunks are sized
        by it)."""
        counts = [self.base.get("n_modes",
                                Design.__dataclass_fields__["n_modes"]
                                .default)]
        counts += [v for name, values in self.vary if name == "n_modes"
                   for v in np.asarray(values).tolist()]
        return max(max(c) if isinstance(c, (tuple, list)) else int(c)
                   for c in counts)

    @property
    def max_tau(self) -> float:
        """The longest window of any design (s): a normal distribution's
        as its mean + 8 sd."""
        taus = [self.base.get("tau",
                              Design.__dataclass_fields__["tau"].default)]
        taus += self.varied_extremes("tau")
        for name, kind, a, b in self.sample:
            if name == "tau":
                taus.append(b if kind == "uniform" else a + 8 * b)
        return float(np.max(taus))

    def varied_extremes(self, field: str) -> list:
        """The values a --vary axis of ``field`` takes that bound the
        rest: a linear axis's ends, a list's values ([] if not varied)."""
        out = []
        for name, values in self.vary:
            if name == field:
                out += [values.start, values.stop] if isinstance(
                    values, LinearAxis) else np.asarray(values).tolist()
        return out

    @property
    def fields(self) -> tuple:
        """Names of the varied and sampled fields (output columns)."""
        return tuple(n for n, _ in self.vary) + tuple(
            s[0] for s in self.sample)

    def inputs(self) -> dict:
        """Everything that makes the sweep, under output names: seed,
        samples per grid point, the grids, the distributions and the
        fixed fields (the rest is the thesis design); JSON-ready."""
        vary = {}
        for name, values in self.vary:
            vary[column_name(name)] = (
                {"start": values.start, "stop": values.stop,
                 "count": values.count} if isinstance(values, LinearAxis)
                else {"values": np.asarray(values).tolist()})
        sample = {column_name(name): {"distribution": kind,
                                      **dict(zip(_PARAMETERS[kind],
                                                 (a, b)))}
                  for name, kind, a, b in self.sample}
        out = {"seed": self.seed, "samples": self.samples,
               "designs": self.size, "vary": vary, "sample": sample,
               "fixed": design_fields.describe(self.base),
               "backend": self.backend}
        if self.model != "eq23":
            out["model"] = self.model
            out["settings"] = design_fields.describe(self.settings)
        return out

    def describe(self) -> list[str]:
        """The inputs in words, one line each (the CSV's comments), in
        the unit system shown (``model.names.units_shown``)."""
        inputs = shown_data(self.inputs())
        lines = [f"designs: {self.size}"]
        for key, grid in inputs["vary"].items():
            if "start" in grid:
                lines.append(f"vary {key}: {grid['count']} values from "
                             f"{grid['start']:.12g} to {grid['stop']:.12g}")
            else:
                lines.append(f"vary {key}: " + ", ".join(
                    _text(v) for v in grid["values"]))
        if self.sample:
            lines.append(f"samples: {self.samples} per grid point, seed "
                         f"{self.seed}")
        for key, law in inputs["sample"].items():
            kind = law["distribution"]
            p, q = _PARAMETERS[kind]
            lines.append(f"sample {key} ~ {kind}({p} {law[p]:.12g}, {q} "
                         f"{law[q]:.12g})")
        for key, value in {**inputs["fixed"],
                           **inputs.get("settings", {})}.items():
            lines.append(f"fixed {key} = {value}")
        return lines


#: Parameter names of each distribution, as the summary records them.
_PARAMETERS = {"normal": ("mean", "sd"), "uniform": ("low", "high")}


def _text(value) -> str:
    return f"{value:.12g}" if isinstance(value, float) else str(value)


def _draw(spec: SweepSpec, which: int, first: int, last: int) -> np.ndarray:
    """Samples first..last-1 of sampled field ``which`` (sample k is
    design k: with a grid, each design draws its own values)."""
    _, kind, a, b = spec.sample[which]
    out = np.empty(last - first)
    block = first // SAMPLE_BLOCK
    done = 0
    while first + done < last:
        rng = np.random.default_rng([spec.seed, which, block])
        values = rng.normal(a, b, SAMPLE_BLOCK) if kind == "normal" \
            else rng.uniform(a, b, SAMPLE_BLOCK)
        start = first + done - block * SAMPLE_BLOCK
        take = min(SAMPLE_BLOCK - start, last - first - done)
        out[done:done + take] = values[start:start + take]
        done += take
        block += 1
    return out


def chunk_inputs(spec: SweepSpec, first: int, last: int) -> dict:
    """The varied and sampled field values of designs first..last-1."""
    index = np.arange(first, last, dtype=np.int64)
    point = index // spec.samples
    values = {}
    if spec.vary:
        grid = np.unravel_index(point, spec.grid_shape)
        for (name, axis), k in zip(spec.vary, grid):
            values[name] = axis[k]
    for which, (name, _, _, _) in enumerate(spec.sample):
        values[name] = _draw(spec, which, first, last)
    return values


def evaluate_chunk(spec: SweepSpec, first: int, last: int) -> dict:
    """Evaluate designs first..last-1; returns the output columns: the
    varied and sampled fields (output names), then RESULT_COLUMNS."""
    inputs = chunk_inputs(spec, first, last)
    design = thesis_design(**{**spec.base, **inputs})
    ev = evaluate(design, backend=spec.backend)
    shape = (last - first,)
    out = {column_name(n): np.broadcast_to(inputs[n], shape)
           for n in spec.fields}
    out.update({"y3_max_in": np.broadcast_to(ev.y3_max, shape),
                "t_max_s": np.broadcast_to(ev.t_max, shape),
                "psi_lb_s": np.broadcast_to(ev.psi, shape),
                "v0_in_s": np.broadcast_to(ev.v0, shape),
                "status": np.broadcast_to(ev.status, shape)})
    return out


@dataclass
class Summary:
    """Running statistics of max y3 over the designs evaluated with
    status 0; failed designs are counted by status."""

    threshold: float | None = None
    exceed: int = 0
    #: max y3 (in) of the designs with status 0.
    y3: RunningMoments = field(default_factory=RunningMoments)
    #: status code -> designs that ended with it (0 excluded).
    failed: dict = field(default_factory=dict)

    def add(self, columns: dict) -> None:
        ok = count_failures(self.failed, columns["status"])
        y = np.asarray(columns["y3_max_in"])[ok]
        self.y3.add(y)
        if self.threshold is not None:
            self.exceed += int(np.sum(y > self.threshold))

    def merge(self, other: "Summary") -> None:
        """Add another chunk's summary (a worker's)."""
        self.exceed += other.exceed
        self.y3.merge(other.y3)
        for code, count in other.failed.items():
            self.failed[code] = self.failed.get(code, 0) + count

    @property
    def n(self) -> int:
        return self.y3.count

    @property
    def n_failed(self) -> int:
        return sum(self.failed.values())

    def as_dict(self) -> dict:
        """n (designs with status 0: the statistics are theirs),
        n_failed and n_failed_by_status (status code -> count), the
        mean, sample sd, min and max of max y3 (None where there is
        nothing to compute them from), and with a threshold p_exceed =
        P(max y3 > threshold) and its 95 % Wilson interval
        p_exceed_ci95."""
        n = self.n
        out = {"n": n, "n_failed": self.n_failed,
               "n_failed_by_status": dict(sorted(self.failed.items())),
               "y3_max_mean_in": self.y3.mean,
               "y3_max_sd_in": self.y3.sd,
               "y3_max_min_in": self.y3.minimum if n else None,
               "y3_max_max_in": self.y3.maximum if n else None}
        if self.threshold is not None:
            out["threshold_in"] = self.threshold
            out["p_exceed"] = self.exceed / n if n else None
            out["p_exceed_ci95"] = list(wilson_interval(self.exceed, n)) \
                if n else None
        return out


def count_failures(failed: dict, status) -> np.ndarray:
    """Add a chunk's failed designs to ``failed`` (status code -> count);
    returns the mask of the designs with status 0."""
    status = np.asarray(status)
    ok = status == 0
    codes, counts = np.unique(status[~ok], return_counts=True)
    for code, count in zip(codes.tolist(), counts.tolist()):
        failed[code] = failed.get(code, 0) + count
    return ok


def _centres(vary, sample) -> dict:
    """A value each swept design field takes (a --vary axis's first, a
    --sample's mean or midpoint), to check the fixed fields with."""
    out = {}
    for name, values in vary:
        values = [values.start] if isinstance(values, LinearAxis) \
            else np.asarray(values).ravel().tolist()
        if name in design_fields.FIELDS and values:
            out[name] = values[0]
    for name, kind, a, b in sample:
        if name in design_fields.FIELDS:
            out[name] = a if kind == "normal" else 0.5 * (a + b)
    return out


def make_spec(vary=(), sample=(), samples=None, seed=0, base=None,
              backend="compiled", model="eq23", settings=None) -> SweepSpec:
    """A SweepSpec from --vary / --sample texts (or parsed tuples);
    ``base`` the fixed fields (Design field -> value); ``model`` eq23,
    hertz or newton; ``settings`` the fixed chatter settings (preload,
    min_open, damping -> value; hertz and newton only)."""
    vary = tuple(parse_vary(v) if isinstance(v, str) else v for v in vary)
    sample = tuple(parse_sample(s) if isinstance(s, str) else s
                   for s in sample)
    names = [n for n, _ in vary]
    if len(set(names)) != len(names):
        raise SweepError("--vary: a field is varied twice")
    if len({s[0] for s in sample}) != len(sample):
        raise SweepError("--sample: a field is sampled twice")
    if set(names) & {s[0] for s in sample}:
        raise SweepError("a field cannot be both varied and sampled")
    base, settings = check_fixed(base, settings,
                                 _centres(vary, sample))
    fixed = (set(base) | set(settings)) & (set(names)
                                           | {s[0] for s in sample})
    if fixed:
        raise SweepError(f"{', '.join(sorted(fixed))}: fixed by a design "
                         f"option and varied or sampled too")
    swept = set(names) | {s[0] for s in sample}
    check_model(model, backend, swept | set(settings))
    check_used(model, swept | set(base))
    check_elastic(model, swept, settings)
    check_preload(settings.get("preload"), base, swept)
    if samples is None:
        samples = 1000 if sample else 1
    if isinstance(samples, bool) or not isinstance(samples, int) or \
            not 1 <= samples <= MAX_DESIGNS:
        raise SweepError(f"--samples: found {samples!r}, expected an "
                         f"integer from 1 to {MAX_DESIGNS:,}")
    if samples > 1 and not sample:
        raise SweepError("--samples needs --sample")
    if isinstance(seed, bool) or not isinstance(seed, int) or \
            not 0 <= seed < 2**64:
        raise SweepError(f"--seed: found {seed!r}, expected an integer "
                         f"from 0 to 2^64 - 1")
    spec = SweepSpec(base=base, vary=vary, sample=sample, samples=samples,
                     seed=seed, backend=backend, model=model,
                     settings=settings)
    check_chatter_modes(model, base.get("n_modes"))
    steps = [settings["dt"]] if "dt" in settings else []
    check_dt(steps + spec.varied_extremes("dt"), spec.max_modes,
             "--dt" if "dt" in settings else "--vary dt", model)
    if spec.size > MAX_DESIGNS:
        raise SweepError(f"the sweep has {spec.size:.3g} designs "
                         f"({' x '.join(str(n) for n in spec.grid_shape)}"
                         f"{f' x {samples}' if sample else ''}), expected at "
                         f"most {MAX_DESIGNS:,}")
    return spec
