!> Normal modes of a uniform Bernoulli-Euler beam, four end conditions.
!>
!> Codes: 1 clamped-free, 2 clamped-clamped, 3 clamped-pinned,
!> 4 pinned-pinned.  Modes are normalised to int X^2 dx = L.  The
!> hyperbolic terms are evaluated with e^{-kL} factored out through
!> g = (1 - sigma) e^{kL}, which has a closed form without cancellation,
!> so no term exceeds a few units for any mode number.
module model_beam_modes
  use contactsep_kinds, only: wp
  implicit none
  private
  public :: eigenvalue, sigma_parts, mode_value, static_flexibility

  !> End condition codes.
  integer, parameter, public :: clamped_free = 1, clamped_clamped = 2, &
      clamped_pinned = 3, pinned_pinned = 4
  real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp

contains

  !> The frequency equation divided by cosh x: bounded, same roots.
  pure function frequency_function(end, x) result(f)
    integer, intent(in) :: end
    real(wp), intent(in) :: x
    real(wp) :: f, q

    select case (end)
    case (clamped_free)
      q = exp(-x)
      f = cos(x) + 2.0_wp * q / (1.0_wp + q * q)
    case (clamped_clamped)
      q = exp(-x)
      f = cos(x) - 2.0_wp * q / (1.0_wp + q * q)
    case default
      q = exp(-2.0_wp * x)
      f = cos(x) * (1.0_wp - q) / (1.0_wp + q) - sin(x)
    end select
  end function frequency_function

  !> k_jL, root j of the frequency equation, by bisection to adjacent
  !> doubles (pinned-pinned: j pi).
  pure function eigenvalue(end, j) result(kl)
    integer, intent(in) :: end, j
    real(wp) :: kl, lo, hi, mid, lo_sign

    select case (end)
    case (clamped_free)
      lo = (j - 1) * pi
      hi = j * pi
    case (clamped_clamped)
      lo = j * pi
      hi = (j + 1) * pi
    case (clamped_pinned)
      lo = j * pi
      hi = (j + 0.5_wp) * pi
    case default
      kl = j * pi
      return
    end select
    lo_sign = sign(1.0_wp, frequency_function(end, lo))
    do
      mid = 0.5_wp * (lo + hi)
      if (mid == lo .or. mid == hi) exit
      if (sign(1.0_wp, frequency_function(end, mid)) == lo_sign) then
        lo = mid
      else
        hi = mid
      end if
    end do
    if (abs(frequency_function(end, lo)) <= &
        abs(frequency_function(end, hi))) then
      kl = lo
    else
      kl = hi
    end if
  end function eigenvalue

  !> sigma_j and g_j = (1 - sigma_j) e^{k_jL} without cancellation.
  pure subroutine sigma_parts(end, kl, sigma, g)
    integer, intent(in) :: end
    real(wp), intent(in) :: kl
    real(wp), intent(out) :: sigma, g
    real(wp) :: q, c, s, den

    q = exp(-kl)
    c = cos(kl)
    s = sin(kl)
    if (end == clamped_free) then
      den = 1.0_wp + q * q + 2.0_wp * q * c
      sigma = (1.0_wp - q * q - 2.0_wp * q * s) / den
      g = 2.0_wp * (q + c + s) / den
    else
      den = 1.0_wp - q * q - 2.0_wp * q * s
      sigma = (1.0_wp + q * q - 2.0_wp * q * c) / den
      g = 2.0_wp * (c - s - q) / den
    end if
  end subroutine sigma_parts

  !> X_j(xi L) of the mode with eigenvalue kl (sigma, g from sigma_parts).
  pure function mode_value(end, kl, sigma, g, xi) result(x)
    integer, intent(in) :: end
    real(wp), intent(in) :: kl, sigma, g, xi
    real(wp) :: x, z

    z = kl * xi
    if (end == pinned_pinned) then
      x = sqrt(2.0_wp) * sin(z)
    else
      x = 0.5_wp * g * exp(z - kl) + 0.5_wp * (1.0_wp + sigma) * exp(-z) &
          - cos(z) + sigma * sin(z)
    end if
  end function mode_value

  !> G(xi) = y(a) EI/(F L^3) under a point load F at a = xi L (exact).
  pure function static_flexibility(end, xi) result(g)
    integer, intent(in) :: end
    real(wp), intent(in) :: xi
    real(wp) :: g, b

    b = 1.0_wp - xi
    select case (end)
    case (clamped_free)
      g = xi**3 / 3.0_wp
    case (clamped_clamped)
      g = xi**3 * b**3 / 3.0_wp
    case (clamped_pinned)
      g = xi**3 * b**2 * (3.0_wp + b) / 12.0_wp
    case default
      g = xi**2 * b**2 / 3.0_wp
    end select
  end function static_flexibility

end module model_beam_modes
