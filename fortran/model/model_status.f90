!> Per-design status codes of the general model.  One home in Fortran;
!> python/contactsep/model/status.py mirrors them (pinned by a test).
module model_status
  implicit none
  private

  !> The design was evaluated.
  integer, parameter, public :: status_ok = 0
  !> y1(x1, t) does not reach the gap within one period of the upper
  !> member's first mode (or starts at or below it).
  integer, parameter, public :: status_no_impact = 1
  !> A value out of range (size, density, modulus, contact point, e, N,
  !> tau, end condition).
  integer, parameter, public :: status_invalid_input = 2
  !> A result overflowed.
  integer, parameter, public :: status_not_finite = 3
  !> The extremes of y3 could not be resolved to 1e-12 within the search's
  !> work budget (too many modes for the window, or a window too long).
  integer, parameter, public :: status_unresolved = 4
end module model_status
