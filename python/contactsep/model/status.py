"""Per-design status codes of the general model (one home; the Fortran
kernel's fortran/model/model_status.f90 mirrors them, pinned by a test)."""

#: The design was evaluated.
OK = 0
#: y1(x1, t) does not reach the gap within one period of the upper
#: member's first mode (or starts at or below it).
NO_IMPACT = 1
#: A value out of range (a size, density or modulus <= 0 or not finite,
#: a contact point outside (0, L] or at a support of the loaded member,
#: e outside [0, 1], N < 1, tau <= 0, an unknown end condition).
INVALID_INPUT = 2
#: A result overflowed.
NOT_FINITE = 3
#: The extremes of y3 could not be resolved to 1e-12 within the search's
#: work budget (too many modes for the window, or a window too long).
UNRESOLVED = 4

#: Code -> one-line meaning.
MESSAGES = {
    OK: "ok",
    NO_IMPACT: "no impact: y1(x1, t) never reaches the gap within one "
               "period of the upper contact's first mode",
    INVALID_INPUT: "invalid input: a value out of range",
    NOT_FINITE: "a result is not finite (overflow)",
    UNRESOLVED: "the extremes of y3 could not be resolved to 1e-12 of "
                "sum |c_j| within the search's work budget: shorten tau "
                "or use fewer modes",
}


def no_impact(ys: float, gap: float) -> str:
    """NO_IMPACT's message for one design, naming its ys and gap."""
    return (f"no impact: the upper contact released from ys = {ys:g} in "
            f"never reaches the separator's surface at gap = {gap:g} in "
            f"within one period of its first mode (a gap at or above ys, "
            f"or below the swing)")


def explain(code: int, design) -> str:
    """The message of one design's status, naming the fields that led to
    it where one did (NO_IMPACT: ys and gap; UNRESOLVED: tau and N)."""
    if code == NO_IMPACT:
        return no_impact(float(design.ys), float(design.gap))
    if code == UNRESOLVED:
        return (f"tau: found {float(design.tau):g} s with N = "
                f"{design.n_modes}: {MESSAGES[code]}")
    return MESSAGES[code]
