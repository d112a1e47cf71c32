!> Section, mass and frequency constants of the three beams.
!>
!> The contact (XL, B, H, RHO), the separator (XL2, ...) and the lower
!> contact (XL3, ...) are all uniform beams; the listing computes the
!> same five quantities for each with the same expressions, kept here in
!> the listing's grouping so that every bit agrees.  Units are the
!> listing's: inches, lb/ft^3, psi; 386.4 in/s^2 turns weight into mass.
module contactsep_beam_properties
  use contactsep_kinds, only: wp
  use contactsep_constants, only: gravity, cubic_inches_per_cubic_foot
  implicit none
  private
  public :: beam, beam_properties

  !> Constants of one beam (suffix 2 or 3 in the listing for the others).
  type :: beam
    !> RHOC = RHO/1728: density in lb/in^3.
    real(wp) :: density = 0.0_wp
    !> A = B*H: cross-section area.
    real(wp) :: area = 0.0_wp
    !> WM = RHOC*A*XL/386.4: mass of the whole beam.
    real(wp) :: mass = 0.0_wp
    !> EYE = B*H**3/12: second moment of area.
    real(wp) :: inertia = 0.0_wp
    !> W = sqrt(E*EYE*386.4/(A*RHOC)); mode j's frequency is W*V(j)**2/XL**2.
    real(wp) :: w = 0.0_wp
  end type beam

contains

  !> Constants of a beam of length xl, width b, thickness h, density rho
  !> (lb/ft^3) and Young's modulus e.
  pure function beam_properties(xl, b, h, rho, e) result(this)
    real(wp), intent(in) :: xl, b, h, rho, e
    type(beam) :: this

    this%density = rho / cubic_inches_per_cubic_foot
    this%area = b * h
    this%mass = (this%density * this%area * xl) / gravity
    this%inertia = (b * (h**3)) / 12.0_wp
    this%w = sqrt((e * (this%inertia * gravity)) &
        / (this%area * this%density))
  end function beam_properties

end module contactsep_beam_properties
