!> f2py entry of the contact dynamics: one call runs one simulation.
module chatter_api
  use contactsep_kinds, only: wp
  use chatter_moreau_jean, only: moreau_jean
  use chatter_hertz, only: hertz
  implicit none
  private
  public :: run_moreau_jean, run_hertz

contains

  !> Moreau-Jean (see chatter_moreau_jean); q, v are copied, not changed.
  subroutine run_moreau_jean(n, k, m, p, h, g0, q0, v0, e, dt, theta, &
      steps, stride, samples, t_out, g_out, e_out, p_out, first, status)
    integer, intent(in) :: n, k, steps, stride, samples
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k), q0(n), v0(n)
    real(wp), intent(in) :: e, dt, theta
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), p_out(k, samples)
    !> First episode of contact 1: time, impulse (-1: none).
    real(wp), intent(out) :: first(2)
    integer, intent(out) :: status
    real(wp) :: q(n), v(n)

    q = q0
    v = v0
    call moreau_jean(n, k, m, p, h, g0, q, v, e, dt, theta, steps, &
        stride, samples, t_out, g_out, e_out, p_out, first, status)
  end subroutine run_moreau_jean

  !> Hertz splitting (see chatter_hertz); q, v are copied, not changed.
  subroutine run_hertz(n, k, m, p, h, g0, q0, v0, stiffness, chi, dt, &
      steps, stride, samples, t_out, g_out, e_out, p_out, first)
    integer, intent(in) :: n, k, steps, stride, samples
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k), q0(n), v0(n)
    real(wp), intent(in) :: stiffness, chi, dt
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), p_out(k, samples)
    !> First episode of contact 1: time, impulse (-1: none).
    real(wp), intent(out) :: first(2)
    real(wp) :: q(n), v(n)

    q = q0
    v = v0
    call hertz(n, k, m, p, h, g0, q, v, stiffness, chi, dt, steps, &
        stride, samples, t_out, g_out, e_out, p_out, first)
  end subroutine run_hertz

end module chatter_api
