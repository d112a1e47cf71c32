!> Constants every layer shares, one home each, in the working precision
!> of the build that compiles them.  python/contactsep/constants.py
!> mirrors them (pinned by tests/shared/test_constants.py).  The values
!> are the listing's own literals, so the restored core that uses them
!> computes the same bits as the transcription.
module contactsep_constants
  use contactsep_kinds, only: wp
  implicit none
  private

  !> Acceleration of gravity (in/s^2): weight to mass (Appendix B;
  !> the listing's 386.4).
  real(wp), parameter, public :: gravity = 386.4_wp
  !> Cubic inches in a cubic foot: a deck's lb/ft^3 to lb/in^3 (the
  !> listing's 1728).
  real(wp), parameter, public :: cubic_inches_per_cubic_foot = 1728.0_wp
  !> End of the listing's lower-contact history (s): the listing's TAU.
  real(wp), parameter, public :: listing_tau = 0.060_wp
end module contactsep_constants
