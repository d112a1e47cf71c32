!> Hertz contact between the modal members by Strang splitting: half
!> kick of the contact forces, the exact modal flow over dt, half kick.
!> Twin: contactsep/chatter/steppers.py.
module chatter_hertz
  use contactsep_kinds, only: wp
  implicit none
  private
  public :: hertz

contains

  !> F = k delta^{3/2} (1 + chi delta'), F >= 0, delta = -gap.
  pure subroutine contact_forces(k, stiffness, chi, gap, rate, force)
    integer, intent(in) :: k
    real(wp), intent(in) :: stiffness, chi, gap(k), rate(k)
    real(wp), intent(out) :: force(k)
    integer :: i

    do i = 1, k
      if (gap(i) < 0.0_wp) then
        force(i) = max(stiffness * (-gap(i))**1.5_wp &
            * (1.0_wp - chi * rate(i)), 0.0_wp)
      else
        force(i) = 0.0_wp
      end if
    end do
  end subroutine contact_forces

  !> Integrate `steps` steps of dt; sample every `stride` steps.
  pure subroutine hertz(n, k, m, p, h, g0, q, v, stiffness, chi, dt, &
      steps, stride, samples, t_out, g_out, e_out, p_out, first)
    integer, intent(in) :: n, k
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k)
    real(wp), intent(inout) :: q(n), v(n)
    !> Hertz constant k (lb/in^1.5) and damping chi (s/in).
    real(wp), intent(in) :: stiffness, chi, dt
    integer, intent(in) :: steps, stride, samples
    !> Sampled times, gaps, energy (with the contacts'), and impulses
    !> (force x dt) summed over each sample.
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), p_out(k, samples)
    !> Contact 1's first episode: the start of its first step with a
    !> force, and the impulse of its consecutive steps with one.
    real(wp), intent(out) :: first(2)
    real(wp) :: c(n), s(n), force(k), gap(k), qn(n)
    integer :: step, i, sample, episode

    c = cos(p * dt)
    s = sin(p * dt)
    p_out = 0.0_wp
    first = -1.0_wp
    episode = 0
    t_out(1) = 0.0_wp
    gap = matmul(h, q) + g0
    g_out(:, 1) = gap
    e_out(1) = energy()
    do step = 1, steps
      gap = matmul(h, q) + g0
      call contact_forces(k, stiffness, chi, gap, matmul(h, v), force)
      sample = (step - 1) / stride + 2
      if (sample <= samples) p_out(:, sample) = p_out(:, sample) &
          + force * dt
      if (force(1) > 0.0_wp .and. episode == 0) then
        episode = 1
        first(1) = (step - 1) * dt
        first(2) = 0.0_wp
      end if
      if (episode == 1) then
        if (force(1) > 0.0_wp) then
          first(2) = first(2) + force(1) * dt
        else
          episode = 2
        end if
      end if
      do i = 1, k
        v = v + 0.5_wp * dt * h(i, :) * force(i) / m
      end do
      qn = q * c + v / p * s
      v = -q * p * s + v * c
      q = qn
      gap = matmul(h, q) + g0
      call contact_forces(k, stiffness, chi, gap, matmul(h, v), force)
      do i = 1, k
        v = v + 0.5_wp * dt * h(i, :) * force(i) / m
      end do
      if (mod(step, stride) == 0) then
        sample = step / stride + 1
        t_out(sample) = step * dt
        g_out(:, sample) = gap
        e_out(sample) = energy()
      end if
    end do

  contains

    pure function energy() result(total)
      real(wp) :: total, g(k)

      g = matmul(h, q) + g0
      total = 0.5_wp * sum(m * (v**2 + (p * q)**2)) &
          + 0.4_wp * stiffness * sum(max(-g, 0.0_wp)**2.5_wp)
    end function energy

  end subroutine hertz

end module chatter_hertz
