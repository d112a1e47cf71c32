!> Moreau-Jean time stepping of the modal members with unilateral
!> contacts and Newton's impact law (theta-method, velocity level, the
!> one-step LCP solved exactly).  Twin: contactsep/chatter/steppers.py.
module chatter_moreau_jean
  use contactsep_kinds, only: wp
  use chatter_lcp, only: solve_lcp
  use chatter_status, only: status_ok, status_lcp_unsolved, &
      status_crossings_full, status_energy_bound, status_interrupted
  use chatter_stop, only: stop_requested, stop_check_every
  implicit none
  private
  public :: moreau_jean

contains

  !> Integrate `steps` steps of dt; sample every `stride` steps.
  !> The positions are linear within a step (q += dt (theta v+ +
  !> (1 - theta) v)), so each crossing of the open threshold is found
  !> there by linear interpolation, and each gap's largest value is its
  !> largest at a step's end.
  !> Hard bounds (issue 31): status_energy_bound when the energy at a
  !> sample or a stop check exceeds energy_bound (or is not a number),
  !> status_interrupted when chatter_stop's flag is set.
  subroutine moreau_jean(n, k, m, p, h, g0, q, v, e, dt, theta, &
      steps, stride, samples, threshold, max_cross, t_out, g_out, e_out, &
      p_out, first, crossings, n_cross, gap_max, energy_bound, status)
    !> Modes (all members stacked) and contacts (1 or 2).
    integer, intent(in) :: n, k
    !> Mass and frequency of every mode; contact Jacobian; gap offsets.
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k)
    !> Initial modal displacements and velocities (overwritten).
    real(wp), intent(inout) :: q(n), v(n)
    real(wp), intent(in) :: e, dt, theta
    integer, intent(in) :: steps, stride, samples
    !> A contact is open while its gap exceeds threshold (in).
    real(wp), intent(in) :: threshold
    integer, intent(in) :: max_cross
    !> Sampled times, gaps, energy, and impulses summed over each sample.
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), p_out(k, samples)
    !> Contact 1's first episode: the time its first step ends, the
    !> impulse of its consecutive contact steps.
    real(wp), intent(out) :: first(2)
    !> crossings(:, i) = time, +c (contact c opens) or -c (it closes).
    real(wp), intent(out) :: crossings(2, max_cross)
    integer, intent(out) :: n_cross
    !> gap_max(:, c) = largest gap c at a step's end and its time.
    real(wp), intent(out) :: gap_max(2, k)
    !> The energy's hard bound (in lb).
    real(wp), intent(in) :: energy_bound
    !> status_ok, status_lcp_unsolved (the LCP had no solution),
    !> status_crossings_full (the crossings filled their table), or a
    !> hard bound's status (above).
    integer, intent(out) :: status
    real(wp) :: stiff(n), w(n), v_free(n), v_new(n), u(k), gap(k)
    real(wp) :: d(2, 2), b(2), z(2), hw(k, n), gap_new(k)
    integer :: step, i, j, s, active(2), na
    logical :: ok, touched
    integer :: episode

    status = status_ok
    first = -1.0_wp
    episode = 0
    stiff = m * p**2
    w = 1.0_wp / (m + dt**2 * theta**2 * stiff)
    do i = 1, k
      hw(i, :) = h(i, :) * w
    end do
    p_out = 0.0_wp
    t_out = -1.0_wp
    g_out = 0.0_wp
    e_out = 0.0_wp
    t_out(1) = 0.0_wp
    g_out(:, 1) = matmul(h, q) + g0
    e_out(1) = 0.5_wp * sum(m * v**2 + stiff * q**2)
    crossings = 0.0_wp
    n_cross = 0
    gap = matmul(h, q) + g0
    gap_max(1, :) = gap
    gap_max(2, :) = 0.0_wp
    do step = 1, steps
      u = matmul(h, v)
      v_free = w * (m * v - dt * stiff * q &
          - dt**2 * theta * (1.0_wp - theta) * stiff * v)
      na = 0
      do i = 1, k
        ! closed and not separating: the impulse's work, P (1-e) u_k / 2,
        ! is then never positive (energy never grows).  "Separating" is
        ! beyond round-off: a closed contact at rest has u = 0 +- the
        ! round-off of v_free + impulse, which cancel (a contact skipped
        ! for a step sinks by dt^2 F / M)
        if (gap(i) + 0.5_wp * dt * u(i) <= 0.0_wp .and. u(i) <= 64.0_wp &
            * epsilon(1.0_wp) * sum(abs(h(i, :) * v_free))) then
          na = na + 1
          active(na) = i
        end if
      end do
      v_new = v_free
      s = (step - 1) / stride + 2
      if (na == 0 .and. episode == 1) episode = 2
      if (na > 0) then
        do i = 1, na
          do j = 1, na
            d(i, j) = sum(hw(active(i), :) * h(active(j), :))
          end do
          b(i) = sum(h(active(i), :) * v_free) + e * u(active(i))
        end do
        call solve_lcp(na, d, b, z, ok)
        if (.not. ok) then
          status = status_lcp_unsolved
          return
        end if
        touched = .false.
        do i = 1, na
          if (active(i) == 1 .and. z(i) > 0.0_wp) touched = .true.
        end do
        if (touched .and. episode == 0) then
          episode = 1
          first(1) = step * dt
          first(2) = 0.0_wp
        end if
        if (episode == 1) then
          if (touched) then
            do i = 1, na
              if (active(i) == 1) first(2) = first(2) + z(i)
            end do
          else
            episode = 2
          end if
        end if
        do i = 1, na
          v_new = v_new + hw(active(i), :) * z(i)
          if (s <= samples) p_out(active(i), s) = &
              p_out(active(i), s) + z(i)
        end do
      end if
      q = q + dt * (theta * v_new + (1.0_wp - theta) * v)
      v = v_new
      gap_new = matmul(h, q) + g0
      do i = 1, k
        if ((gap(i) > threshold) .neqv. (gap_new(i) > threshold)) then
          if (n_cross >= max_cross) then
            status = status_crossings_full
            return
          end if
          n_cross = n_cross + 1
          crossings(1, n_cross) = (step - 1) * dt + dt * (gap(i) &
              - threshold) / (gap(i) - gap_new(i))
          crossings(2, n_cross) = merge(i, -i, gap_new(i) > threshold)
        end if
        if (gap_new(i) > gap_max(1, i)) then
          gap_max(1, i) = gap_new(i)
          gap_max(2, i) = step * dt
        end if
      end do
      gap = gap_new
      if (mod(step, stride) == 0) then
        s = step / stride + 1
        t_out(s) = step * dt
        g_out(:, s) = gap
        e_out(s) = 0.5_wp * sum(m * v**2 + stiff * q**2)
        if (.not. e_out(s) <= energy_bound) status = status_energy_bound
      end if
      if (mod(step, stop_check_every) == 0) then
        if (.not. 0.5_wp * sum(m * v**2 + stiff * q**2) <= energy_bound) &
            status = status_energy_bound
        if (stop_requested /= 0) status = status_interrupted
      end if
      if (status /= status_ok) return
    end do
    if (.not. 0.5_wp * sum(m * v**2 + stiff * q**2) <= energy_bound) &
        status = status_energy_bound
  end subroutine moreau_jean

end module chatter_moreau_jean
