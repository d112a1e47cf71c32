!> The exact modal flow of the adaptive stepper (chatter_adaptive): its
!> tables, the flow over a tabled step, the gaps and the energy of a
!> state, the bounds of the gaps' curvature (B_c) and of their departure
!> from the chord over a step, and the gap anywhere within a step (the
!> state at its end flowed back).  The kernels (advance, dot,
!> modal_energy) are apart, so that they vectorise: no aliasing between
!> dummy arguments.
module chatter_adaptive_flow
  use contactsep_kinds, only: wp
  use chatter_adaptive_state, only: adaptive_run
  use chatter_hertz_series, only: series_energy, series_law_energy
  use chatter_contact_law, only: law_energy
  implicit none
  private
  public :: table, flow, gaps, energy, amplitude_bounds, chord
  public :: end_rates, gap_at, monotone
  public :: dot, advance, safe_time

contains

  !> Rotation by the exact flow over tau for every mode.
  subroutine table(run, slot, tau)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: slot
    real(wp), intent(in) :: tau
    integer :: j

    ! libm's scalar cos and sin (within an ulp), not libmvec's vector
    ! ones (up to 4 ulp) that -O3 calls here otherwise: every flight
    ! step rotates by this table, and the stepper's answers were made
    ! with libm's (docs/chatter.md)
    !GCC$ novector
    do j = 1, run%n
      run%tab_c(j, slot) = cos(run%p(j) * tau)
      run%tab_s(j, slot) = sin(run%p(j) * tau) / run%p(j)
      run%tab_p(j, slot) = run%p(j) * sin(run%p(j) * tau)
    end do
  end subroutine table

  !> The exact flow of the moving modes over a tabled step; the gaps
  !> and their rates after it in gap_new, rate_new.
  subroutine flow(run, slot)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: slot
    real(wp) :: sums(4)

    call advance(run%moving, run%q, run%v, run%tab_c(:, slot), &
        run%tab_s(:, slot), run%tab_p(:, slot), run%ht(:, 1), &
        run%ht(:, run%h2), sums)
    run%gap_new(:) = sums(1:run%k) + run%g_still
    run%rate_new(:) = sums(3:2 + run%k)
  end subroutine flow

  !> The gaps of the current state.
  function gaps(run) result(g)
    type(adaptive_run), intent(in) :: run
    real(wp) :: g(run%k)
    integer :: j

    do j = 1, run%k
      g(j) = dot(run%moving, run%ht(:, j), run%q) + run%g_still(j)
    end do
  end function gaps

  !> Modal energy and the contacts' (2/5) k delta^{5/2} (in lb).
  subroutine energy(run, total)
    type(adaptive_run), intent(inout) :: run
    real(wp), intent(out) :: total
    integer :: j

    ! the modal energy changes only at kicks
    if (.not. run%e_fresh) run%e_modal = modal_energy(run%n, run%m, &
        run%p, run%q, run%v)
    run%e_fresh = .true.
    total = run%e_modal
    if (run%series .and. run%law%plastic) then
      total = series_law_energy(run%k, run%law, run%cmat, run%gap, total)
      return
    end if
    if (run%series) then
      total = total + series_energy(run%k, run%stiffness, run%cmat, &
          run%gap, run%law%linear)
      return
    end if
    do j = 1, run%k
      if (run%law%plastic .or. run%law%linear) then
        total = total + law_energy(run%law, j, -run%gap(j))
      else if (run%gap(j) < 0.0_wp) then
        total = total + 0.4_wp * run%stiffness * run%gap(j)**2 &
            * sqrt(-run%gap(j))
      end if
    end do
  end subroutine energy

  !> B_c = sum |h_cj| p_j^2 a_j over the moving modes, into run%bound.
  subroutine amplitude_bounds(run)
    type(adaptive_run), intent(inout) :: run
    real(wp) :: amp(run%n)
    integer :: j, nm

    nm = run%moving
    amp(1:nm) = run%p(1:nm)**2 * sqrt(run%q(1:nm)**2 &
        + (run%v(1:nm) / run%p(1:nm))**2)
    do j = 1, run%k
      run%bound(j) = sum(abs(run%ht(1:nm, j)) * amp(1:nm))
    end do
  end subroutine amplitude_bounds

  !> Amplitudes of the modes in the segment that ends at the current
  !> state (the flow keeps them).
  subroutine segment_amplitudes(run)
    type(adaptive_run), intent(inout) :: run
    integer :: nm

    nm = run%moving
    run%amp(1:nm) = sqrt(run%q(1:nm)**2 + (run%v(1:nm) &
        / run%p(1:nm))**2)
  end subroutine segment_amplitudes

  !> The largest departure of gap c (order 0) or of its rate (order
  !> 1) from its chord over an interval of length w: mode j departs by
  !> at most min(p_j^2 w^2 / 8, 2) times its amplitude in it, |h_cj|
  !> a_j p_j^order (a_j from segment_amplitudes).
  real(wp) function chord(run, c, w, order)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: c, order
    real(wp), intent(in) :: w
    integer :: j

    if (.not. run%amp_now) call segment_amplitudes(run)
    run%amp_now = .true.
    chord = 0.0_wp
    do j = 1, run%moving
      chord = chord + abs(run%ht(j, c)) * run%amp(j) * run%p(j)**order &
          * min(0.125_wp * (run%p(j) * w)**2, 2.0_wp)
    end do
  end function chord

  !> g' keeps one sign on an interval with end rates da, dz, the rate
  !> departing from its chord by at most margin.
  logical function monotone(da, dz, margin)
    real(wp), intent(in) :: da, dz, margin

    monotone = min(da, dz) > margin .or. max(da, dz) < -margin
  end function monotone

  !> Rate of gap c at the step's start (the state flowed back by the
  !> table) and at its end.
  function end_rates(run, c, slot) result(rates)
    type(adaptive_run), intent(in) :: run
    integer, intent(in) :: c, slot
    real(wp) :: rates(2)
    integer :: nm

    nm = run%moving
    rates(1) = dot_product(run%ht(1:nm, c), run%v(1:nm) &
        * run%tab_c(1:nm, slot) + run%q(1:nm) * run%tab_p(1:nm, slot))
    rates(2) = dot_product(run%ht(1:nm, c), run%v(1:nm))
  end function end_rates

  !> Gap c and its rate at tau <= 0 from the state at the step's end
  !> (before any kick there): the exact flow backwards.
  subroutine gap_at(run, c, tau, g, d)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: c
    real(wp), intent(in) :: tau
    real(wp), intent(out) :: g, d
    real(wp) :: cs(run%moving), sn(run%moving)
    integer :: nm

    nm = run%moving
    run%counts(3) = run%counts(3) + 1
    cs = cos(run%p(1:nm) * tau)
    sn = sin(run%p(1:nm) * tau)
    g = sum(run%ht(1:nm, c) * (run%q(1:nm) * cs &
        + run%v(1:nm) / run%p(1:nm) * sn)) + run%g_still(c)
    d = sum(run%ht(1:nm, c) * (run%v(1:nm) * cs &
        - run%q(1:nm) * run%p(1:nm) * sn))
  end subroutine gap_at

  !> The exact flow of modes 1..nm over a step: (q, v) rotated by the
  !> step's cos, sin / p and p sin.
  !> sums = h1.q, h2.q, h1.v, h2.v after the flow, in the same pass.
  pure subroutine advance(nm, q, v, c, s, ps, h1, h2, sums)
    integer, intent(in) :: nm
    real(wp), intent(inout) :: q(nm), v(nm)
    real(wp), intent(in) :: c(nm), s(nm), ps(nm), h1(nm), h2(nm)
    real(wp), intent(out) :: sums(4)
    real(wp) :: qn, vn, g1, g2, u1, u2
    integer :: j

    g1 = 0.0_wp
    g2 = 0.0_wp
    u1 = 0.0_wp
    u2 = 0.0_wp
    !$omp simd private(qn, vn) reduction(+:g1, g2, u1, u2)
    do j = 1, nm
      qn = q(j) * c(j) + v(j) * s(j)
      vn = v(j) * c(j) - q(j) * ps(j)
      q(j) = qn
      v(j) = vn
      g1 = g1 + h1(j) * qn
      g2 = g2 + h2(j) * qn
      u1 = u1 + h1(j) * vn
      u2 = u2 + h2(j) * vn
    end do
    sums = [g1, g2, u1, u2]
  end subroutine advance

  !> a . b, a sum the compiler vectorises.
  pure function dot(nm, a, b) result(total)
    integer, intent(in) :: nm
    real(wp), intent(in) :: a(nm), b(nm)
    real(wp) :: total
    integer :: j

    total = 0.0_wp
    !$omp simd reduction(+:total)
    do j = 1, nm
      total = total + a(j) * b(j)
    end do
  end function dot

  !> Kinetic and strain energy of the modes, sum m (v^2 + p^2 q^2) / 2.
  pure function modal_energy(nm, m, p, q, v) result(total)
    integer, intent(in) :: nm
    real(wp), intent(in) :: m(nm), p(nm), q(nm), v(nm)
    real(wp) :: total
    integer :: j

    total = 0.0_wp
    !$omp simd reduction(+:total)
    do j = 1, nm
      total = total + m(j) * (v(j)**2 + (p(j) * q(j))**2)
    end do
    total = 0.5_wp * total
  end function modal_energy

  !> The first root s > 0 of g + u s - b s^2 / 2 (g >= 0): no function
  !> with these value and rate and |g''| <= b goes below 0 before it
  !> (a gap at 0 with nothing moving, as the untouched lower contact
  !> before the impact, never does).
  pure function safe_time(g, u, b) result(s)
    real(wp), intent(in) :: g, u, b
    real(wp) :: s

    if (g < 0.0_wp) then
      s = 0.0_wp
    else if (b <= 0.0_wp) then
      s = merge(huge(1.0_wp), g / max(-u, tiny(1.0_wp)), u >= 0.0_wp)
    else if (u >= 0.0_wp) then
      s = (u + sqrt(u * u + 2.0_wp * b * g)) / b
    else
      s = 2.0_wp * g / (sqrt(u * u + 2.0_wp * b * g) - u)
    end if
  end function safe_time

end module chatter_adaptive_flow
