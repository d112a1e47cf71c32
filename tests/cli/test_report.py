"""``contactsep report``: one self-contained HTML page for a design, its
preload answer planted (a known threshold: tests/planted_preload.py) so
that the page, not the search, is under test; opened in headless
Chromium as a person would."""

from __future__ import annotations

import html.parser
import subprocess

import numpy as np
import pytest
from browser import chromium, headless

from contactsep.cli import main
from contactsep.model.fields import FIELDS, OUTPUT_NAMES

pytest.importorskip("matplotlib")

#: A small steel relay of the design family (tests/design_family.py),
#: N = 4 so that its two releases take seconds.
RELAY = ["--L1", "1.2", "--b1", "0.25", "--h1", "0.01", "--L3", "1.2",
         "--b3", "0.25", "--h3", "0.01", "--L2", "0.3", "--b2", "0.1",
         "--h2", "0.05", "--ys", "0.02", "--E1", "30e6", "--E2", "30e6",
         "--E3", "30e6", "--gamma1", "0.283", "--gamma2", "0.283",
         "--gamma3", "0.283", "--n-modes", "4", "--workers", "1"]


class _Page(html.parser.HTMLParser):
    """The page's images, links, scripts and table cells."""

    def __init__(self):
        super().__init__()
        self.images, self.links, self.scripts, self.cells = [], [], 0, []
        self._cell = None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "img":
            self.images.append(attrs.get("src", ""))
        elif tag in ("a", "link") and "href" in attrs:
            self.links.append(attrs["href"])
        elif tag == "script":
            self.scripts += 1
        elif tag == "td":
            self._cell = ""

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data

    def handle_endtag(self, tag):
        if tag == "td" and self._cell is not None:
            self.cells.append(self._cell)
            self._cell = None


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    """The report of RELAY, planted preloads, without and with a
    tolerance (the module's tests read the same two pages)."""
    from planted_preload import plant
    monkeypatch = pytest.MonkeyPatch()      # module-wide: the fixture's
    plant(monkeypatch)
    folder = tmp_path_factory.mktemp("report")
    paths = folder / "plain.html", folder / "robust.html"
    try:
        assert main(["report", *RELAY, "-o", str(paths[0])]) == 0
        assert main(["report", *RELAY, "--tolerance",
                     "h2=normal(0.05,0.001)", "--samples", "20",
                     "--p-target", "0.2", "-o", str(paths[1])]) == 0
    finally:
        monkeypatch.undo()
    return [p.read_text() for p in paths], paths


def _parsed(text):
    parser = _Page()
    parser.feed(text)
    return parser


def test_the_page_is_self_contained(page):
    """No script, no link outside the page; every image inside it."""
    for text in page[0]:
        parsed = _parsed(text)
        assert parsed.scripts == 0 and parsed.links == []
        assert parsed.images and all(
            src.startswith("data:image/png;base64,") for src in parsed.images)
        assert text.startswith("<!DOCTYPE html>")


def test_every_input_with_its_unit(page):
    """Each field the relay was given, under its output name, beside its
    unit as the names table prints it (an independent reading: the
    options typed above)."""
    cells = _parsed(page[0][0]).cells
    given = dict(zip(RELAY[0:-4:2], RELAY[1:-4:2]))
    for option, value in given.items():
        field = option[2:]
        name = OUTPUT_NAMES.get(field, field)
        at = cells.index(name)
        assert float(cells[at + 1]) == float(value)
        assert cells[at + 2] == FIELDS[field][1]


def test_the_answer_and_the_command(page):
    """The planted threshold's answer (a quarter of the largest preload
    x (1 + 1/N) x (1 + dt/1e-7), found to 1 % by the search) is on the
    page, with the command that made it and the version."""
    from planted_preload import threshold

    from contactsep import __version__
    from contactsep.model import Design
    text = page[0][0]
    assert f"contactsep {__version__}" in text
    assert "contactsep report --L1 1.2" in text
    design = Design(L1=1.2, b1=0.25, h1=0.01, L3=1.2, b3=0.25, h3=0.01,
                    L2=0.3, b2=0.1, h2=0.05, ys=0.02, E1=30e6, E2=30e6,
                    E3=30e6, gamma1=0.283, gamma2=0.283, gamma3=0.283,
                    n_modes=4)
    cells = _parsed(text).cells
    answer = float(cells[cells.index("smallest preload at N = 4") + 1]
                   .split()[0])
    truth = threshold(design, {})
    assert truth <= answer <= truth * 1.0101


def test_the_robust_page_has_its_p_open_curve(page):
    """20 samples show p_target 0.2 (none open: Wilson's upper end 0.161):
    the curve of the preloads tried, its answer marked."""
    text = page[0][1]
    assert "the robust preload" in text
    assert "robust answer" in _parsed(text).cells
    assert len(_parsed(text).images) == len(_parsed(page[0][0]).images) + 1


def test_a_robust_search_not_shown_draws_no_empty_curve(tmp_path,
                                                        monkeypatch):
    """20 samples cannot show the default p_target 0.01: the page says
    how many it needs (381, Wilson's bound) instead of drawing axes with
    nothing on them."""
    from planted_preload import plant
    plant(monkeypatch)
    path = tmp_path / "not-shown.html"
    assert main(["report", *RELAY, "--tolerance", "h2=normal(0.05,0.001)",
                 "--samples", "20", "-o", str(path)]) == 0
    text = path.read_text()
    assert "Not searched: 20 samples cannot show p_open" in text
    assert "it needs 381 or more" in text
    plain = _parsed(text)
    assert "robust answer" not in plain.cells
    assert len(plain.images) == 2       # the two releases only


@pytest.mark.skipif(chromium() is None, reason="needs Chromium (CI "
                    "installs Debian's chromium)")
def test_the_page_opens_in_a_browser(page, tmp_path):
    """Headless Chromium loads the page: its DOM has every image, and a
    screenshot shows the figures (far more than a blank page's ink)."""
    matplotlib_image = pytest.importorskip("matplotlib.image")
    path = page[1][1]
    browser = headless(tmp_path / "profile")
    dom = subprocess.run(browser + ["--dump-dom", path.as_uri()],
                         capture_output=True, text=True, timeout=120)
    assert dom.returncode == 0, dom.stderr[-2000:]
    assert dom.stdout.count("<img") == len(_parsed(page[0][1]).images)
    shot = tmp_path / "page.png"
    done = subprocess.run(browser + [f"--screenshot={shot}",
                                     "--window-size=1200,3000",
                                     path.as_uri()],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and shot.exists(), done.stderr[-2000:]
    pixels = matplotlib_image.imread(shot)[..., :3]
    ink = np.mean(np.any(pixels < 0.9, axis=-1))
    assert ink > 0.03, ink


def test_the_page_in_si_is_the_inch_pound_page_converted(page, tmp_path,
                                                        monkeypatch):
    """--units si: the relay typed in SI (its bare numbers in m, Pa,
    kg/m^3) gives the same planted answer, shown in N, its inputs in SI
    units, the tolerance's bare numbers read in m; no force or length is
    left in lb or in (the search's grid, "2^(k/4) lb", is its name)."""
    import re

    from planted_preload import plant
    plant(monkeypatch)
    metre, newton = 0.0254, 4.4482216152605
    pascal, kg_m3 = newton / metre**2, 0.45359237 / metre**3
    factors = {"L": metre, "b": metre, "h": metre, "y": metre,
               "E": pascal, "g": kg_m3}
    si = []
    for option, value in zip(RELAY[0:-4:2], RELAY[1:-4:2]):
        si += [option, repr(float(value) * factors[option[2]])]
    path = tmp_path / "si.html"
    assert main(["report", *si, *RELAY[-4:], "--units", "si", "--tolerance",
                 f"h2=normal({0.05 * metre!r},{0.001 * metre!r})",
                 "--samples", "20", "--p-target", "0.2", "-o",
                 str(path)]) == 0
    text = path.read_text()
    us_cells, si_cells = (_parsed(t).cells for t in (page[0][1], text))
    key = "smallest preload at N = 4"
    us_answer = us_cells[us_cells.index(key) + 1]
    si_answer = si_cells[si_cells.index(key) + 1]
    assert us_answer.endswith(" lb") and si_answer.endswith(" N")
    assert float(si_answer.split()[0]) == pytest.approx(
        float(us_answer.split()[0]) * newton, rel=1e-5)
    at = si_cells.index("L1")
    assert float(si_cells[at + 1]) == pytest.approx(1.2 * metre, rel=1e-12)
    assert si_cells[at + 2] == "m"
    assert "units: m, N, s, Pa, kg/m^3" in text
    body = re.sub(r"<[^>]+>", " ", text.split("<footer>")[0])
    left = re.findall(r"\d (?:lb|in|psi)\b", body)
    assert not left, left
