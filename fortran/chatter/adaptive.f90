!> The three beams' contacts, fast: fixed steps of dt only where a
!> contact may close, every run of steps in which none can merged into
!> one exact modal flow, and the circuit's open and close instants found
!> on the exact flow.  Two contact laws:
!>
!> * Hertz (law_hertz): the fixed-step splitting of chatter_hertz (half
!>   kick, exact flow, half kick) on the same grid of dt;
!> * Newton (law_newton): the exact flow over dt/2, the impulse of
!>   Newton's law at the contacts closed at the midpoint and not
!>   separating (0 <= u+ + e u- complementary to P >= 0, the one-step
!>   LCP solved exactly, as chatter_moreau_jean solves it), the exact
!>   flow over dt/2: Moreau-Jean's velocity-level law with the modal
!>   flow exact, so that modes far above 1/dt keep their phase.
!>
!> No twin: tested against chatter_hertz and chatter_moreau_jean, and
!> analytic cases (tests/chatter/test_adaptive.py).
!>
!> Free flight.  Where no contact force acts, a step is the exact flow,
!> so m steps are one flow over m dt.  With
!> B_c = sum_j |h_cj| p_j^2 a_j >= |g_c''| (a_j the mode's amplitude,
!> constant in flight), g_c(t + s) >= g_c + g_c' s - B_c s^2 / 2 > 0
!> before the first root s* of that parabola: no contact can close, and
!> the fixed-step stepper would meet no force, at any grid point before
!> it.  The flight step is the largest tabled multiple of dt (a power of
!> two, or the whole run) that fits in s* and the end.  Where a contact
!> may close, the step is the law's fixed step.
!>
!> Samples.  The steps do not depend on the samples asked for: the
!> samples inside a flight step are a copy of the state at its start
!> flowed to them (the first by its own rotation, the rest by the
!> stride's table), so that the trajectory, and every summary figure
!> found on it, is the same bits for any number of samples (cutting the
!> flight at the samples changed the round-off, which a rattling
!> preloaded contact amplifies: issue 26).
!>
!> A preloaded start (n_moving < n): the modes n_moving+1..n (separator
!> and lower contact) are in static equilibrium with the preload, which
!> the exact dynamics keeps; they are held still, their contact's force
!> not applied, until contact 1 may close.  From that step on every
!> mode moves and every force acts.
!>
!> Crossings.  Over any step, the gap's motion between the kicks is the
!> exact flow of the state after the first kick (the state at the step's
!> end, before the second kick, flowed back).  If both ends of a step
!> lie on one side of the open threshold with a margin B_c dt^2 / 8 (the
!> largest departure from the chord of a function with |g''| <= B_c;
!> in fixed steps first with a bound of B_c from the energy, which costs
!> nothing), or with the tighter margin sum_j |h_cj| a_j
!> min(p_j^2 dt^2 / 8, 2) (each mode departs from its own chord by at
!> most that), the gap cannot have crossed it; otherwise the step is
!> searched by bisection with the tighter margin and each crossing
!> refined by Newton's method with bisection on the exact flow.  The
!> largest value of the last contact's (the lower) gap is found the same
!> way, to max_tol; those searches wait for the end of the run, when the
!> running largest value excludes most of the steps that might top it.
!>
!> The parts: the run's state (adaptive_state.f90), the exact flow and
!> its bounds (adaptive_flow.f90), the largest gap (adaptive_gap_max.f90),
!> the crossings (adaptive_crossings.f90), the contact laws' fixed steps
!> (adaptive_laws.f90); here the driver: the choice of each step and
!> the flight steps.
module chatter_adaptive
  use contactsep_kinds, only: wp
  use chatter_status, only: status_ok, status_interrupted
  use chatter_stop, only: stop_requested, stop_check_every
  use chatter_adaptive_state, only: adaptive_run, max_level, head, &
      max_waiting
  use chatter_adaptive_flow, only: table, flow, gaps, energy, &
      amplitude_bounds, dot, advance, safe_time
  use chatter_adaptive_crossings, only: watch
  use chatter_adaptive_gap_max, only: search_waiting
  use chatter_adaptive_laws, only: hertz_step, newton_step
  use chatter_adaptive_event, only: event_start, event_watch
  use chatter_hertz_series, only: series_forces, series_law_forces
  use chatter_contact_law, only: contact_law, law_setup, law_plastic_work
  implicit none
  private
  public :: adaptive, law_hertz, law_newton

  !> Contact laws.
  integer, parameter :: law_hertz = 1, law_newton = 2

contains

  !> Integrate `steps` steps of dt from t = 0; sample every `stride`.
  subroutine adaptive(law, n, k, m, p, h, g0, cmat, q, v, stiffness, &
      chi, restitution, dt, steps, stride, samples, threshold, n_moving, &
      energy_bound, max_cross, t_out, g_out, e_out, first, crossings, &
      n_cross, gap_max, counts, status, contact, book, stop_open)
    !> law_hertz or law_newton.
    integer, intent(in) :: law
    !> Modes (all members stacked) and contacts (1 or 2).
    integer, intent(in) :: n, k
    !> Mass and frequency of every mode; contact Jacobian; gap offsets.
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k)
    !> Hertz: the static correction's series flexibilities (in/lb;
    !> 0: the plain truncation; chatter_hertz_series).
    real(wp), intent(in) :: cmat(k, k)
    !> Initial modal displacements and velocities (overwritten: final).
    real(wp), intent(inout) :: q(n), v(n)
    !> Hertz constant k (lb/in^1.5; 0 for Newton), damping chi (s/in),
    !> Newton's coefficient of restitution, step dt (s).
    real(wp), intent(in) :: stiffness, chi, restitution, dt
    integer, intent(in) :: steps, stride, samples
    !> A contact is open while its gap exceeds threshold (in).
    real(wp), intent(in) :: threshold
    !> Modes 1..n_moving move from the start (n: all); see the module.
    integer, intent(in) :: n_moving
    !> A bound on the modal energy over the run (in lb).
    real(wp), intent(in) :: energy_bound
    integer, intent(in) :: max_cross
    !> Sampled times, gaps, energy (with the contacts').
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples)
    !> Contact 1's first episode: the start of its first step with a
    !> force (Hertz) or its first impulse's time (Newton, a midpoint),
    !> and the impulse of its consecutive steps with one.
    real(wp), intent(out) :: first(2)
    !> crossings(:, i) = time, +c (contact c opens) or -c (it closes).
    real(wp), intent(out), target :: crossings(2, max_cross)
    integer, intent(out) :: n_cross
    !> gap_max(:, c) = largest gap c over the window and its time.
    real(wp), intent(out) :: gap_max(2, k)
    !> Flight steps, fixed steps, flow evaluations of the searches.
    integer, intent(out) :: counts(3)
    !> status_ok, status_crossings_full (the table filled up),
    !> status_lcp_unsolved (Newton: the contact LCP had no solution),
    !> status_energy_bound (a fixed step took the energy past
    !> energy_bound, chatter_adaptive_crossings' watch_fixed),
    !> status_stopped_at_event (stop_open: chatter_adaptive_event) or
    !> status_interrupted (chatter_stop's flag, read every
    !> stop_check_every passes of the loop).
    integer, intent(out) :: status
    !> Hertz: the whole force law (chatter_contact_law; without it,
    !> Hertz's with stiffness and chi), and the energy book: dissipated
    !> energy, the contacts' stored energy at the end (in lb).
    type(contact_law), intent(in), optional :: contact
    real(wp), intent(out), optional :: book(2)
    !> Stop at the first discontinuity event: once the circuit has been
    !> open this long (s; chatter_adaptive_event); < 0 or absent: never.
    real(wp), intent(in), optional :: stop_open

    type(adaptive_run) :: run
    real(wp) :: e_end
    real(wp) :: span, safe
    integer :: step, i_next, level, c, sample, units, passes, first_in
    real(wp), allocatable :: q_copy(:), v_copy(:)

    t_out = 0.0_wp
    g_out = 0.0_wp
    e_out = 0.0_wp
    crossings = 0.0_wp
    call start(run, n, k, m, p, h, g0, q, v, stiffness, chi, &
        restitution, dt, steps, stride, threshold, n_moving, &
        energy_bound, max_cross)
    call law_setup(run%law, stiffness, chi, 0.0_wp, 0.0_wp, 0.0_wp)
    if (present(contact)) run%law = contact
    allocate(q_copy(n), v_copy(n))
    if (law == law_hertz) call correct(run, cmat)
    run%crossings => crossings
    if (present(stop_open)) call event_start(run, stop_open)
    sample = 1
    t_out(1) = 0.0_wp
    g_out(:, 1) = sampled_gaps(run)
    call energy(run, e_out(1))
    step = 0
    passes = 0
    do while (step < steps)
      passes = passes + 1
      if (mod(passes, stop_check_every) == 0) then
        if (stop_requested /= 0) run%status = status_interrupted
        if (run%status /= status_ok) exit
      end if
      i_next = steps
      ! a flight step if no (considered) contact is closed
      units = 0
      if (.not. any_closed(run)) then
        if (.not. run%amp_fresh) then
          call amplitude_bounds(run)
          run%amp_fresh = .true.
        end if
        if (.not. run%rate_fresh) then
          do c = 1, k
            run%rate(c) = dot(run%moving, run%ht(:, c), run%v)
          end do
          run%rate_fresh = .true.
        end if
        safe = huge(1.0_wp)
        do c = 1, considered(run)
          safe = min(safe, safe_time(run%gap(c) + run%shift(c), &
              run%rate(c), run%bound(c)))
        end do
        if (safe / dt >= real(i_next - step, wp)) then
          units = i_next - step
        else
          units = int(safe / dt)
        end if
      end if
      if (units >= 1) then
        ! the whole run from its start, else the largest power of two
        if (units == steps .and. step == 0) then
          level = 0
        else
          level = 1
          do while (level < run%levels)
            if (2**level > units) exit
            level = level + 1
          end do
          units = 2**(level - 1)
        end if
        ! the state at the step's start, if a sample falls inside it
        first_in = -1
        if (sample < samples) then
          if (sample * stride < step + units) then
            first_in = sample * stride - step
            q_copy(:) = run%q
            v_copy(:) = run%v
          end if
        end if
        call flow(run, level)
        span = real(units, wp) * dt
        run%t_now = real(step + units, wp) * dt
        run%counts(1) = run%counts(1) + 1
        do c = 1, considered(run)
          call watch(run, c, run%gap(c), run%gap_new(c), span, level, &
              run%t_now, run%bound(c))
        end do
        if (run%episode == 1) run%episode = 2
        run%gap(:) = run%gap_new
        run%rate(:) = run%rate_new
        step = step + units
      else
        call thaw(run)
        run%counts(2) = run%counts(2) + 1
        if (law == law_newton) then
          call newton_step(run, step)
        else
          call hertz_step(run, step)
        end if
        step = step + 1
      end if
      ! the samples this step reached (a flight step may pass several)
      do while (sample < samples)
        if (sample * stride > step) exit
        sample = sample + 1
        t_out(sample) = real((sample - 1) * stride, wp) * dt
        if ((sample - 1) * stride == step) then
          g_out(:, sample) = sampled_gaps(run)
          call energy(run, e_out(sample))
        else
          call sample_within(run, q_copy, v_copy, first_in, &
              g_out(:, sample), e_out(sample))
          first_in = 0
        end if
      end do
      if (run%status == status_ok) call event_watch(run, &
          real(step, wp) * dt)
      if (run%status /= status_ok) exit
    end do
    call search_waiting(run)
    if (present(book)) then
      run%e_fresh = .false.
      call energy(run, e_end)
      book(1) = run%damped_work + law_plastic_work(run%law, k)
      book(2) = e_end - run%e_modal
    end if
    q = run%q
    v = run%v
    first = run%first
    n_cross = run%n_cross
    gap_max = run%gap_max
    counts = run%counts
    status = run%status
  end subroutine adaptive

  !> The run's tables and its state at t = 0 (the arguments as
  !> adaptive's).
  subroutine start(run, n, k, m, p, h, g0, q, v, stiffness, chi, &
      restitution, dt, steps, stride, threshold, n_moving, &
      energy_bound, max_cross)
    type(adaptive_run), intent(out) :: run
    integer, intent(in) :: n, k, steps, stride, n_moving, max_cross
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k), q(n), v(n)
    real(wp), intent(in) :: stiffness, chi, restitution, dt, threshold
    real(wp), intent(in) :: energy_bound
    integer :: c, level, levels, moving

    run%n = n
    run%k = k
    run%m = m
    run%p = p
    run%g0 = g0
    run%q = q
    run%v = v
    run%stiffness = stiffness
    run%chi = chi
    run%restitution = restitution
    run%dt = dt
    run%threshold = threshold
    run%energy_bound = energy_bound
    run%max_cross = max_cross
    run%ht = transpose(h)
    allocate(run%half_kick(n, k), run%inv_mh(n, k), run%energy_b(k))
    allocate(run%cmat(k, k), run%shift(k))
    run%cmat(:, :) = 0.0_wp
    run%shift(:) = 0.0_wp
    allocate(run%force(k))
    run%force(:) = 0.0_wp
    do c = 1, k
      run%lo(c) = 1
      run%hi(c) = 0
      do level = n, 1, -1
        if (run%ht(level, c) /= 0.0_wp) run%lo(c) = level
        if (run%ht(level, c) /= 0.0_wp .and. run%hi(c) == 0) &
            run%hi(c) = level
      end do
      run%half_kick(:, c) = 0.5_wp * dt * run%ht(:, c) / m
      run%inv_mh(:, c) = run%ht(:, c) / m
      ! |g''| <= sqrt(2 E sum h^2 p^2 / m) (Cauchy-Schwarz on the modal
      ! energy E): a bound for any state the run can reach
      run%energy_b(c) = sqrt(2.0_wp * energy_bound &
          * sum(run%ht(:, c)**2 * p**2 / m))
    end do
    ! D = H M^-1 H^T: an impulse P changes the contact rates by D P
    allocate(run%coupling(k, k))
    do c = 1, k
      do level = 1, k
        run%coupling(c, level) = sum(run%ht(:, c) * run%inv_mh(:, level))
      end do
    end do
    ! tables: -2 the sample stride, -1 half a step, 0 the whole run,
    ! 1.. powers of two (1, 2, 4, ...) of dt up to the run's length
    levels = 1
    do while (levels < max_level .and. 2**levels <= steps)
      levels = levels + 1
    end do
    run%levels = levels
    allocate(run%tab_c(n, -2:levels), run%tab_s(n, -2:levels), &
        run%tab_p(n, -2:levels))
    call table(run, -2, real(stride, wp) * dt)
    call table(run, -1, 0.5_wp * dt)
    call table(run, 0, real(steps, wp) * dt)
    do level = 1, levels
      call table(run, level, real(2**(level - 1), wp) * dt)
    end do
    allocate(run%waiting(head + 2 * n, max_waiting))

    moving = max(1, min(n_moving, n))
    run%moving = moving
    run%frozen = moving < n
    run%h2 = min(2, k)
    ! the gaps' part from the modes held still
    allocate(run%g_still(k))
    do c = 1, k
      run%g_still(c) = g0(c) + dot(n - moving, run%ht(moving + 1:, c), &
          q(moving + 1:))
    end do
    allocate(run%amp(n), run%bound(k), run%rate(k), &
        run%rate_new(k), run%gap_new(k), run%gap_max(2, k))
    run%gap = gaps(run)
    do c = 1, k
      run%gap_max(1, c) = run%gap(c)
      run%gap_max(2, c) = 0.0_wp
    end do
  end subroutine start

  !> The static correction (Hertz): the series flexibilities, and while
  !> frozen the shift of the considered contact's gap by the still
  !> contacts' forces (their static equilibrium's, from the gaps at the
  !> start): with the correction, contact 1's Hertz element closes where
  !> g_1 + C_12 lambda_2 < 0, not g_1 < 0.
  subroutine correct(run, cmat)
    type(adaptive_run), intent(inout) :: run
    real(wp), intent(in) :: cmat(run%k, run%k)
    real(wp) :: force(run%k), stiff(run%k), depth(run%k)
    integer :: c, d

    run%cmat(:, :) = cmat
    run%series = any(cmat /= 0.0_wp)
    if (.not. run%series) return
    if (run%law%plastic) then
      ! Thornton's elements (memory as at the start)
      stiff = 1.0_wp
      call series_law_forces(run%k, run%law, stiff, cmat, run%gap, force, &
          depth)
    else
      stiff = run%stiffness
      call series_forces(run%k, stiff, cmat, run%gap, force, &
          run%law%linear)
    end if
    ! the forces at the start (a preload's): sampled_gaps's, and the
    ! physical gaps are the largest so far
    run%force(:) = force
    run%gap_max(1, :) = sampled_gaps(run)
    if (.not. run%frozen) return
    do c = 1, considered(run)
      do d = considered(run) + 1, run%k
        run%shift(c) = run%shift(c) + cmat(c, d) * force(d)
      end do
    end do
  end subroutine correct

  !> The gaps a sample records: the modal gaps, plus with the static
  !> correction the series springs' C lambda (the physical gaps).
  !> run%force holds the forces at the current state: the last fixed
  !> step's end forces (0 after a flight step, which no force precedes),
  !> or while frozen the still contacts' (correct()).
  function sampled_gaps(run) result(g)
    type(adaptive_run), intent(in) :: run
    real(wp) :: g(run%k)

    g = run%gap
    if (run%series) g = g + matmul(run%cmat, run%force)
  end function sampled_gaps

  !> A sample inside a flight step: the copy (q, v) of the state flowed
  !> on to it, by units steps of its own rotation (the step's first
  !> sample, from the step's start) or by the stride's table (units 0:
  !> the next ones).  No force acts in flight: the modal energy is the
  !> step's, and run%force, which sampled_gaps adds, holds through it.
  subroutine sample_within(run, q, v, units, g, e)
    type(adaptive_run), intent(inout) :: run
    real(wp), intent(inout) :: q(run%n), v(run%n)
    integer, intent(in) :: units
    real(wp), intent(out) :: g(run%k), e
    real(wp) :: cs(run%n), sn(run%n), ps(run%n), tau, sums(4)
    real(wp) :: gap_end(run%k)
    integer :: nm, j

    nm = run%moving
    if (units > 0) then
      tau = real(units, wp) * run%dt
      do j = 1, nm
        cs(j) = cos(run%p(j) * tau)
        sn(j) = sin(run%p(j) * tau) / run%p(j)
        ps(j) = run%p(j) * sin(run%p(j) * tau)
      end do
      call advance(nm, q, v, cs, sn, ps, run%ht(:, 1), &
          run%ht(:, run%h2), sums)
    else
      call advance(nm, q, v, run%tab_c(:, -2), run%tab_s(:, -2), &
          run%tab_p(:, -2), run%ht(:, 1), run%ht(:, run%h2), sums)
    end if
    gap_end = run%gap
    run%gap(:) = sums(1:run%k) + run%g_still
    g = sampled_gaps(run)
    call energy(run, e)
    run%gap(:) = gap_end
  end subroutine sample_within

  !> Contacts whose forces act: all, or contact 1 while frozen.
  integer function considered(run)
    type(adaptive_run), intent(in) :: run

    considered = merge(1, run%k, run%frozen)
  end function considered

  !> Is a considered contact closed (a force may act)?
  logical function any_closed(run)
    type(adaptive_run), intent(in) :: run

    any_closed = any(run%gap(1:considered(run)) &
        + run%shift(1:considered(run)) < 0.0_wp)
  end function any_closed

  !> Every mode moves from the first fixed step on.
  subroutine thaw(run)
    type(adaptive_run), intent(inout) :: run

    if (.not. run%frozen) return
    run%frozen = .false.
    run%moving = run%n
    run%amp_fresh = .false.
    run%rate_fresh = .false.
    run%g_still(:) = run%g0
    run%shift(:) = 0.0_wp
  end subroutine thaw

end module chatter_adaptive
