!> Modal frequencies and the modal amplitudes of the released contact.
!>
!> The contact is released from the static deflection curve of a
!> cantilever with a tip load, f(x) = 3*YSTAT/XL**3*(XL*x**2/2 - x**3/6).
!> Its amplitude in cantilever mode j is the integral of f times the mode
!> shape, which the listing evaluates in closed form through U, Q, R and
!> D1..D8 (loop 60).  The expressions are the listing's, term for term:
!> reordering them would change the last bits of P and APE.
module contactsep_modal
  use contactsep_kinds, only: wp
  implicit none
  private
  public :: natural_frequency, release_amplitudes

contains

  !> Circular frequency of a mode with eigenvalue v = kL of a beam of
  !> length xl and frequency constant w: P(I), P2(I) and P3(I).
  elemental function natural_frequency(w, v, xl) result(p)
    real(wp), intent(in) :: w, v, xl
    real(wp) :: p

    p = (w * (v**2)) / (xl**2)
  end function natural_frequency

  !> Amplitude APE(I) of each cantilever mode after release from YSTAT.
  !>
  !> v and alpha are the mode cards' kL and sigma of each mode.
  pure subroutine release_amplitudes(xl, ystat, v, alpha, ape)
    !> Length XL and tip deflection YSTAT of the contact.
    real(wp), intent(in) :: xl, ystat
    real(wp), intent(in) :: v(:), alpha(:)
    real(wp), intent(out) :: ape(:)
    real(wp) :: dog, sinh_v, cosh_v, u, q, r
    real(wp) :: d1, d2, d3, d4, d5, d6, d7, d8, ap, pe
    integer :: i

    do i = 1, size(v)
      ! The listing builds SINH and COSH from EXP (DOG = -V); the
      ! intrinsics round differently, so the EXP form stays.
      dog = -v(i)
      sinh_v = (exp(v(i)) - exp(dog)) / 2.0_wp
      cosh_v = (exp(v(i)) + exp(dog)) / 2.0_wp
      u = v(i) / xl
      q = 2.0_wp / (u**3)
      r = (xl**2) / u
      d1 = (q - r) * cos(v(i)) + ((2.0_wp * (xl * sin(v(i)))) / (u**2)) - q
      d2 = (((2.0_wp * xl) * cos(v(i))) / (u**2)) + (r - q) * sin(v(i))
      d3 = ((3.0_wp * d2) / u) - ((xl**3) * cos(v(i))) / u
      d4 = ((xl**3) * sin(v(i)) / u) - 3.0_wp * d1 / u
      d5 = (r + q) * cosh_v - ((2.0_wp * xl) * sinh_v / (u**2)) - q
      d6 = ((r + q) * sinh_v) - ((2.0_wp * xl) * cosh_v / (u**2))
      d7 = ((xl**3) * cosh_v / u) - 3.0_wp * d6 / u
      d8 = ((xl**3) * sinh_v / u) - 3.0_wp * d5 / u
      ap = ((3.0_wp * ystat) / (xl**3)) * ((d6 - d2) - alpha(i) * (d5 - d1))
      pe = (ystat / (xl**4)) * ((d8 - d4) - alpha(i) * (d7 - d3))
      ape(i) = (ap - pe) / 2.0_wp
    end do
  end subroutine release_amplitudes

end module contactsep_modal
