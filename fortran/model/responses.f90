!> The impulse and the responses of the separator and lower contact
!> (eqs. 12, 13, 20, 23, 24).
module model_responses
  use contactsep_kinds, only: wp
  implicit none
  private
  public :: impulse, separator_velocity, lower_coefficients, mass_ratio, &
      lower_displacement

contains

  !> psi = (1+e) V / sum_j [X1j^2/M1 + X2j^2/M2 + X3j^2/M3] (eqs. 20, 23);
  !> s_i = sum_j X_ij(x_i)^2.
  pure function impulse(e, v, s1, m1, s2, m2, s3, m3) result(psi)
    real(wp), intent(in) :: e, v, s1, m1, s2, m2, s3, m3
    real(wp) :: psi

    psi = (1.0_wp + e) * v / (s1 / m1 + s2 / m2 + s3 / m3)
  end function impulse

  !> v0 = (psi/M2) sum_j X2j(x2)^2 (eq. 12 at the contact point).
  pure function separator_velocity(psi, s2, m2) result(v0)
    real(wp), intent(in) :: psi, s2, m2
    real(wp) :: v0

    v0 = psi * s2 / m2
  end function separator_velocity

  !> c_j = gain X3j(x3)^2 / p3j: y3(x3, t) = sum c_j sin p3j t; gain is
  !> v0/L3 as printed (eqs. 13, 23) or psi/M3 (the impulse form).
  pure subroutine lower_coefficients(gain, values, p3, c)
    real(wp), intent(in) :: gain, values(:), p3(:)
    real(wp), intent(out) :: c(:)

    c = gain * values**2 / p3
  end subroutine lower_coefficients

  !> R = (M2 / sum X2j^2) / (M3 / sum X3j^2) (eq. 24).
  pure function mass_ratio(m2, s2, m3, s3) result(r)
    real(wp), intent(in) :: m2, s2, m3, s3
    real(wp) :: r

    r = (m2 / s2) / (m3 / s3)
  end function mass_ratio

  !> y3(x3, t) = sum_j c_j sin p3j t.
  pure function lower_displacement(c, p, t) result(y)
    real(wp), intent(in) :: c(:), p(:), t
    real(wp) :: y

    y = sum(c * sin(p * t))
  end function lower_displacement

end module model_responses
