"""Status codes of the contact-dynamics solvers, mirrored from their one
home, fortran/chatter/chatter_status.f90 (pinned by
tests/shared/test_constants.py)."""

#: The run reached t_end.
OK = 0
#: Appendix E: stopped at max_impacts impacts before t_end.
IMPACTS_FULL = 1
#: Bad input (n < 1, p <= 0, mass <= 0, X = 0, e outside [0, 1], t_end or
#: zeno_speed < 0, a table size < 1, non-finite).
BAD_INPUT = 2
#: Appendix E: stopped at an impact that would start rest max_rests + 1.
RESTS_FULL = 3
#: The Jacobi eigensolver did not converge.
NO_EIGENBASIS = 4
#: Moreau-Jean: the one-step contact LCP had no solution.
LCP_UNSOLVED = 5
#: Hertz (adaptive): the table of threshold crossings filled up.
CROSSINGS_FULL = 6
#: A stepper stopped: the energy grew past its hard bound (a step too
#: coarse for the contact's stiffness); no circuit figures are valid.
ENERGY_BOUND = 7
#: A stepper stopped: a signal (Ctrl-C, SIGTERM) asked it to.
INTERRUPTED = 8
#: The run ended but broke its energy check (elastic: energy ratio more
#: than 1e-6 from 1; damped: energy gained): unconverged.
UNCONVERGED = 9
#: The adaptive stepper stopped at its first discontinuity event, as
#: asked (``simulate(..., stop_at_event=True)``): the run's figures cover
#: it up to there only (ChatterResult.stopped_s).
STOPPED_AT_EVENT = 10
