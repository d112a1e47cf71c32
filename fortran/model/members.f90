!> Masses, flexural constants and frequencies of the three members.
module model_members
  use contactsep_kinds, only: wp
  use contactsep_constants, only: gravity
  implicit none
  private
  public :: member_constants, frequency

contains

  !> Mass M = gamma A L / g and flexural constant a = sqrt(E I g/(A gamma))
  !> of a uniform beam (III-(1)).
  pure subroutine member_constants(length, width, thickness, gamma, &
      modulus, mass, a)
    !> Length, width, thickness (in), weight density (lb/in^3), E (psi).
    real(wp), intent(in) :: length, width, thickness, gamma, modulus
    !> Mass (lb s^2/in) and flexural constant a (in^2/s).
    real(wp), intent(out) :: mass, a
    real(wp) :: area, inertia

    area = width * thickness
    inertia = width * thickness**3 / 12.0_wp
    mass = gamma * area * length / gravity
    a = sqrt(modulus * inertia * gravity / (area * gamma))
  end subroutine member_constants

  !> p_j = (k_jL)^2 a / L^2 (k = sqrt(p/a)).
  elemental function frequency(kl, a, length) result(p)
    real(wp), intent(in) :: kl, a, length
    real(wp) :: p

    p = kl**2 * (a / length**2)
  end function frequency

end module model_members
