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
end module chatter_status
