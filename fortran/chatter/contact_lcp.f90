!> The one-step complementarity problem of one or two contacts.
module chatter_lcp
  use contactsep_kinds, only: wp
  implicit none
  private
  public :: solve_lcp

contains

  !> z >= 0 with w = a z + b >= 0 and z.w = 0, k = 1 or 2 unknowns,
  !> exactly: the active sets are tried in order and the first that
  !> satisfies the conditions is taken (a is symmetric positive definite,
  !> so exactly one does).  ok is false if none does.
  pure subroutine solve_lcp(k, a, b, z, ok)
    integer, intent(in) :: k
    real(wp), intent(in) :: a(2, 2), b(2)
    real(wp), intent(out) :: z(2)
    logical, intent(out) :: ok
    real(wp) :: w(2), tol, det
    integer :: mask

    tol = 1.0e-12_wp * (maxval(abs(b(1:k))) + tiny(1.0_wp))
    ok = .false.
    do mask = 0, 2**k - 1
      z = 0.0_wp
      select case (mask)
      case (1)
        z(1) = -b(1) / a(1, 1)
      case (2)
        z(2) = -b(2) / a(2, 2)
      case (3)
        det = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)
        z(1) = (-b(1) * a(2, 2) + b(2) * a(1, 2)) / det
        z(2) = (-b(2) * a(1, 1) + b(1) * a(2, 1)) / det
      end select
      w(1:k) = matmul(a(1:k, 1:k), z(1:k)) + b(1:k)
      if (all(z(1:k) >= -tol) .and. all(w(1:k) >= -tol)) then
        z = max(z, 0.0_wp)
        ok = .true.
        return
      end if
    end do
  end subroutine solve_lcp

end module chatter_lcp
