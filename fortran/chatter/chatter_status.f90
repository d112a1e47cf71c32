!> Status codes of the contact-dynamics solvers.  One home in Fortran;
!> python/contactsep/chatter/status.py mirrors them (pinned by a test).
module chatter_status
  implicit none
  private

  !> The run reached t_end.
  integer, parameter, public :: status_ok = 0
  !> Appendix E: stopped at max_impacts impacts before t_end.
  integer, parameter, public :: status_impacts_full = 1
  !> Bad input (n < 1, p <= 0, mass <= 0, X = 0, e outside [0, 1],
  !> t_end or zeno_speed < 0, a table size < 1, non-finite).
  integer, parameter, public :: status_bad_input = 2
  !> Appendix E: stopped at an impact that would start rest max_rests + 1.
  integer, parameter, public :: status_rests_full = 3
  !> The Jacobi eigensolver did not converge.
  integer, parameter, public :: status_no_eigenbasis = 4
  !> Moreau-Jean: the one-step contact LCP had no solution.
  integer, parameter, public :: status_lcp_unsolved = 5
  !> Hertz (adaptive): the table of threshold crossings filled up.
  integer, parameter, public :: status_crossings_full = 6
  !> A stepper stopped: the energy grew past its hard bound (a step too
  !> coarse for the contact's stiffness); no circuit figures are valid.
  integer, parameter, public :: status_energy_bound = 7
  !> A stepper stopped: a signal (Ctrl-C, SIGTERM) asked it to.
  integer, parameter, public :: status_interrupted = 8
  !> The run ended but broke its energy check (elastic: energy ratio
  !> more than 1e-6 from 1; damped: energy gained): unconverged.
  integer, parameter, public :: status_unconverged = 9
  !> The adaptive stepper stopped, asked to (stop_open >= 0), at the end
  !> of the step where the circuit had been open for stop_open: its
  !> first discontinuity event; the figures cover the run up to there.
  integer, parameter, public :: status_stopped_at_event = 10
end module chatter_status
