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
!> two, or the sample stride) that fits in s*, the next sample and the
!> end.  Where a contact may close, the step is the law's fixed step.
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
module chatter_adaptive
  use contactsep_kinds, only: wp
  use chatter_lcp, only: solve_lcp
  use chatter_status, only: status_ok, status_crossings_full, &
      status_lcp_unsolved
  implicit none
  private
  public :: adaptive, law_hertz, law_newton

  !> Contact laws.
  integer, parameter :: law_hertz = 1, law_newton = 2

  !> Flight steps of up to 2^max_level dt.
  integer, parameter :: max_level = 30
  !> Intervals held by a search (depth-first, one split adds one).
  integer, parameter :: max_stack = 400
  !> Relative tolerance of the largest gap.
  real(wp), parameter :: max_tol = 1.0e-6_wp
  !> Steps whose search for the largest gap waits for the end of the run
  !> (by then the running largest gap excludes most of them).
  integer, parameter :: max_waiting = 64
  !> Header of a waiting step: its end time, length, upper bound, gaps
  !> and rates at its ends, moving modes, the still modes' part of gap.
  integer, parameter :: head = 9

contains

  !> Integrate `steps` steps of dt from t = 0; sample every `stride`.
  subroutine adaptive(law, n, k, m, p, h, g0, q, v, stiffness, chi, &
      restitution, dt, steps, stride, samples, threshold, n_moving, &
      energy_bound, max_cross, t_out, g_out, e_out, first, crossings, &
      n_cross, gap_max, counts, status)
    !> law_hertz or law_newton.
    integer, intent(in) :: law
    !> Modes (all members stacked) and contacts (1 or 2).
    integer, intent(in) :: n, k
    !> Mass and frequency of every mode; contact Jacobian; gap offsets.
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k)
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
    real(wp), intent(out) :: crossings(2, max_cross)
    integer, intent(out) :: n_cross
    !> gap_max(:, c) = largest gap c over the window and its time.
    real(wp), intent(out) :: gap_max(2, k)
    !> Flight steps, fixed steps, flow evaluations of the searches.
    integer, intent(out) :: counts(3)
    !> status_ok, status_crossings_full (the table filled up) or
    !> status_lcp_unsolved (Newton: the contact LCP had no solution).
    integer, intent(out) :: status

    real(wp), allocatable :: tab_c(:, :), tab_s(:, :), tab_p(:, :)
    !> The waiting steps: header, then q and v at the step's end.
    real(wp), allocatable :: waiting(:, :)
    integer :: n_waiting
    real(wp) :: ht(n, k), half_kick(n, k), force(k), gap(k), gap_new(k)
    real(wp) :: inv_mh(n, k), coupling(k, k), amp(n)
    !> amp holds the current segment's amplitudes.
    logical :: amp_now
    real(wp) :: rate(k), rate_new(k), bound(k), energy_b(k), g_still(k)
    real(wp) :: t_now, span, safe, e_modal
    integer :: moving, step, levels, i_next, level, c, sample, units
    integer :: episode, h2
    logical :: amp_fresh, kicked, frozen, rate_fresh, e_fresh

    status = status_ok
    n_cross = 0
    counts = 0
    first = -1.0_wp
    episode = 0
    t_out = 0.0_wp
    g_out = 0.0_wp
    e_out = 0.0_wp
    crossings = 0.0_wp
    ht = transpose(h)
    do c = 1, k
      half_kick(:, c) = 0.5_wp * dt * ht(:, c) / m
      inv_mh(:, c) = ht(:, c) / m
      ! |g''| <= sqrt(2 E sum h^2 p^2 / m) (Cauchy-Schwarz on the modal
      ! energy E): a bound for any state the run can reach
      energy_b(c) = sqrt(2.0_wp * energy_bound * sum(ht(:, c)**2 &
          * p**2 / m))
    end do
    ! tables: 0 the stride, 1.. powers of two (1, 2, 4, ...) of dt
    levels = 1
    do while (levels < max_level .and. 2**levels <= steps)
      levels = levels + 1
    end do
    ! D = H M^-1 H^T: an impulse P changes the contact rates by D P
    do c = 1, k
      do level = 1, k
        coupling(c, level) = sum(ht(:, c) * inv_mh(:, level))
      end do
    end do
    ! tables: -1 half a step, 0 the stride, 1.. powers of two of dt
    allocate(tab_c(n, -1:levels), tab_s(n, -1:levels), &
        tab_p(n, -1:levels))
    call table(-1, 0.5_wp * dt)
    call table(0, real(stride, wp) * dt)
    allocate(waiting(head + 2 * n, max_waiting))
    n_waiting = 0
    do level = 1, levels
      call table(level, real(2**(level - 1), wp) * dt)
    end do

    moving = max(1, min(n_moving, n))
    frozen = moving < n
    h2 = min(2, k)
    ! the gaps' part from the modes held still
    do c = 1, k
      g_still(c) = g0(c) + dot(n - moving, ht(moving + 1:, c), &
          q(moving + 1:))
    end do
    gap = gaps()
    rate_fresh = .false.
    e_fresh = .false.
    do c = 1, k
      gap_max(1, c) = gap(c)
      gap_max(2, c) = 0.0_wp
    end do
    sample = 1
    t_out(1) = 0.0_wp
    g_out(:, 1) = gap
    e_out(1) = energy()
    amp_fresh = .false.
    step = 0
    do while (step < steps)
      i_next = min(steps, sample * stride)
      if (sample >= samples) i_next = steps
      ! a flight step if no (considered) contact is closed
      units = 0
      if (.not. any_closed()) then
        if (.not. amp_fresh) then
          call amplitude_bounds(bound)
          amp_fresh = .true.
        end if
        if (.not. rate_fresh) then
          do c = 1, k
            rate(c) = dot(moving, ht(:, c), v)
          end do
          rate_fresh = .true.
        end if
        safe = huge(1.0_wp)
        do c = 1, considered()
          safe = min(safe, safe_time(gap(c), rate(c), bound(c)))
        end do
        if (safe / dt >= real(i_next - step, wp)) then
          units = i_next - step
        else
          units = int(safe / dt)
        end if
      end if
      if (units >= 1) then
        ! the stride from a sample point, else the largest power of two
        if (units == stride .and. mod(step, stride) == 0) then
          level = 0
        else
          level = 1
          do while (level < levels)
            if (2**level > units) exit
            level = level + 1
          end do
          units = 2**(level - 1)
        end if
        call flow(level)
        span = real(units, wp) * dt
        t_now = real(step + units, wp) * dt
        counts(1) = counts(1) + 1
        do c = 1, considered()
          call watch(c, gap(c), gap_new(c), span, level, t_now, &
              bound(c))
        end do
        if (episode == 1) episode = 2
        gap = gap_new
        rate = rate_new
        step = step + units
      else if (law == law_newton) then
        call thaw()
        counts(2) = counts(2) + 1
        call newton_step()
        step = step + 1
      else
        ! a step of the fixed-step splitting, as chatter_hertz takes it
        call thaw()
        counts(2) = counts(2) + 1
        call contact_forces(gap, force)
        if (force(1) > 0.0_wp .and. episode == 0) then
          episode = 1
          first(1) = real(step, wp) * dt
          first(2) = 0.0_wp
        end if
        if (episode == 1) then
          if (force(1) > 0.0_wp) then
            first(2) = first(2) + force(1) * dt
          else
            episode = 2
          end if
        end if
        kicked = any(force /= 0.0_wp)
        call kick()
        call flow(1)
        t_now = real(step + 1, wp) * dt
        call watch_fixed(dt, 1, t_now)
        gap = gap_new
        call contact_forces(gap, force)
        kicked = kicked .or. any(force /= 0.0_wp)
        call kick()
        amp_fresh = amp_fresh .and. .not. kicked
        rate_fresh = .not. kicked
        if (rate_fresh) rate = rate_new
        e_fresh = e_fresh .and. .not. kicked
        step = step + 1
      end if
      if (step == sample * stride .and. sample < samples) then
        sample = sample + 1
        t_out(sample) = real(step, wp) * dt
        g_out(:, sample) = gap
        e_out(sample) = energy()
      end if
      if (status /= status_ok) exit
    end do
    call search_waiting()

  contains

    !> Keep a step whose largest gap may top the running one (upper
    !> bound ub), to be searched at the end; when the table is full, the
    !> step of the lowest bound is searched now instead.
    subroutine wait_for_max(c_, ub, span_, t_end_, ends)
      integer, intent(in) :: c_
      real(wp), intent(in) :: ub, span_, t_end_, ends(4)
      integer :: low

      if (n_waiting < max_waiting) then
        n_waiting = n_waiting + 1
        low = n_waiting
      else
        low = minloc(waiting(3, :), 1)
        if (ub <= waiting(3, low)) then
          call find_max(c_, span_, t_end_, ends)
          return
        end if
        call search_step(low)
      end if
      waiting(1:8, low) = [t_end_, span_, ub, ends, real(moving, wp)]
      waiting(9, low) = g_still(c_)
      waiting(head + 1:head + n, low) = q
      waiting(head + n + 1:, low) = v
    end subroutine wait_for_max

    !> The waiting steps, highest bound first (the running largest gap
    !> grows fastest, and excludes more of the rest).
    subroutine search_waiting()
      integer :: next

      do while (n_waiting > 0)
        next = maxloc(waiting(3, 1:n_waiting), 1)
        call search_step(next)
        waiting(:, next) = waiting(:, n_waiting)
        n_waiting = n_waiting - 1
      end do
    end subroutine search_waiting

    !> Search waiting step i from its own state (then restore the run's).
    subroutine search_step(i)
      integer, intent(in) :: i
      real(wp) :: q_run(n), v_run(n), still_run
      integer :: moving_run

      if (waiting(3, i) <= gap_max(1, k) + tolerance(k)) return
      q_run = q
      v_run = v
      moving_run = moving
      still_run = g_still(k)
      q = waiting(head + 1:head + n, i)
      v = waiting(head + n + 1:, i)
      moving = nint(waiting(8, i))
      g_still(k) = waiting(9, i)
      amp_now = .false.
      call find_max(k, waiting(2, i), waiting(1, i), waiting(4:7, i))
      q = q_run
      v = v_run
      moving = moving_run
      g_still(k) = still_run
      amp_now = .false.
    end subroutine search_step

    !> Every mode moves from the first fixed step on.
    subroutine thaw()
      if (.not. frozen) return
      frozen = .false.
      moving = n
      amp_fresh = .false.
      rate_fresh = .false.
      g_still = g0
    end subroutine thaw

    !> One Newton step: flow dt/2, the impulses, flow dt/2.
    subroutine newton_step()
      real(wp) :: d(2, 2), b(2), z(2), noise, impulse(k), t_mid
      integer :: active(2), na, i, j
      logical :: ok

      call flow(-1)
      t_mid = (real(step, wp) + 0.5_wp) * dt
      call watch_fixed(0.5_wp * dt, -1, t_mid)
      gap = gap_new
      ! closed at the midpoint and not separating beyond the round-off
      ! of the rate (a resting contact has u = 0 +- that)
      na = 0
      do j = 1, k
        noise = 64.0_wp * epsilon(1.0_wp) * sum(abs(ht(:, j) * v))
        if (gap(j) <= 0.0_wp .and. rate_new(j) <= noise) then
          na = na + 1
          active(na) = j
        end if
      end do
      impulse = 0.0_wp
      if (na > 0) then
        do i = 1, na
          do j = 1, na
            d(i, j) = coupling(active(i), active(j))
          end do
          b(i) = (1.0_wp + restitution) * rate_new(active(i))
        end do
        call solve_lcp(na, d, b, z, ok)
        if (.not. ok) then
          status = status_lcp_unsolved
          return
        end if
        do i = 1, na
          impulse(active(i)) = z(i)
          if (z(i) /= 0.0_wp) call axpy(n, z(i), inv_mh(:, active(i)), v)
        end do
      end if
      if (impulse(1) > 0.0_wp .and. episode == 0) then
        episode = 1
        first(1) = t_mid
        first(2) = 0.0_wp
      end if
      if (episode == 1) then
        if (impulse(1) > 0.0_wp) then
          first(2) = first(2) + impulse(1)
        else
          episode = 2
        end if
      end if
      kicked = any(impulse /= 0.0_wp)
      amp_fresh = amp_fresh .and. .not. kicked
      e_fresh = e_fresh .and. .not. kicked
      call flow(-1)
      call watch_fixed(0.5_wp * dt, -1, real(step + 1, wp) * dt)
      gap = gap_new
      rate = rate_new
      rate_fresh = .true.
    end subroutine newton_step

    !> watch() of every contact over a fixed step's flow: the energy
    !> bound first (free), the amplitudes if need be.
    subroutine watch_fixed(span_, slot, t_end_)
      real(wp), intent(in) :: span_, t_end_
      integer, intent(in) :: slot
      real(wp) :: margin
      integer :: j

      do j = 1, k
        margin = 0.125_wp * energy_b(j) * span_**2
        if (crossing_possible(gap(j), gap_new(j), margin) .or. &
            max_possible(j, gap(j), gap_new(j), margin)) then
          call amplitude_bounds(bound)
          call watch(j, gap(j), gap_new(j), span_, slot, t_end_, &
              bound(j))
        end if
      end do
    end subroutine watch_fixed

    !> Rotation by the exact flow over tau for every mode.
    subroutine table(slot, tau)
      integer, intent(in) :: slot
      real(wp), intent(in) :: tau

      tab_c(:, slot) = cos(p * tau)
      tab_s(:, slot) = sin(p * tau) / p
      tab_p(:, slot) = p * sin(p * tau)
    end subroutine table

    !> The exact flow of the moving modes over a tabled step; the gaps
    !> and their rates after it in gap_new, rate_new.
    subroutine flow(slot)
      integer, intent(in) :: slot
      real(wp) :: sums(4)

      call advance(moving, q, v, tab_c(:, slot), tab_s(:, slot), &
          tab_p(:, slot), ht(:, 1), ht(:, h2), sums)
      gap_new = sums(1:k) + g_still
      rate_new = sums(3:2 + k)
    end subroutine flow

    !> Contacts whose forces act: all, or contact 1 while frozen.
    integer function considered()
      considered = merge(1, k, frozen)
    end function considered

    !> Is a considered contact closed (a force may act)?
    logical function any_closed()
      any_closed = any(gap(1:considered()) < 0.0_wp)
    end function any_closed

    !> The gaps of the current state.
    function gaps() result(g)
      real(wp) :: g(k)
      integer :: j

      do j = 1, k
        g(j) = dot(moving, ht(:, j), q) + g_still(j)
      end do
    end function gaps

    !> F = k delta^{3/2} (1 + chi delta'), F >= 0, as chatter_hertz.
    subroutine contact_forces(g, f)
      real(wp), intent(in) :: g(k)
      real(wp), intent(out) :: f(k)
      real(wp) :: depth
      integer :: j

      do j = 1, k
        if (g(j) < 0.0_wp) then
          depth = -g(j)
          f(j) = stiffness * depth * sqrt(depth)
          if (chi /= 0.0_wp) f(j) = max(f(j) &
              * (1.0_wp - chi * dot_product(ht(:, j), v)), 0.0_wp)
        else
          f(j) = 0.0_wp
        end if
      end do
    end subroutine contact_forces

    !> Half a step's kick of the Hertz forces in `force`.
    subroutine kick()
      integer :: j

      do j = 1, k
        if (force(j) /= 0.0_wp) call axpy(n, force(j), half_kick(:, j), v)
      end do
    end subroutine kick

    !> Modal energy and the contacts' (2/5) k delta^{5/2}.
    function energy() result(total)
      real(wp) :: total
      integer :: j

      ! the modal energy changes only at kicks
      if (.not. e_fresh) e_modal = modal_energy(n, m, p, q, v)
      e_fresh = .true.
      total = e_modal
      do j = 1, k
        if (gap(j) < 0.0_wp) total = total &
            + 0.4_wp * stiffness * gap(j)**2 * sqrt(-gap(j))
      end do
    end function energy

    !> B_c = sum |h_cj| p_j^2 a_j over the moving modes.
    subroutine amplitude_bounds(b)
      real(wp), intent(out) :: b(k)
      real(wp) :: amp(n)
      integer :: j

      amp(1:moving) = p(1:moving)**2 * sqrt(q(1:moving)**2 &
          + (v(1:moving) / p(1:moving))**2)
      do j = 1, k
        b(j) = sum(abs(ht(1:moving, j)) * amp(1:moving))
      end do
    end subroutine amplitude_bounds

    !> Could the gap have crossed the threshold within the step?
    !> (Both use a bound of the gap's departure from its chord.)
    logical function crossing_possible(ga, gb, margin)
      real(wp), intent(in) :: ga, gb, margin

      if ((ga > threshold) .neqv. (gb > threshold)) then
        crossing_possible = .true.
      else if (ga > threshold) then
        crossing_possible = min(ga, gb) - margin <= threshold
      else
        crossing_possible = max(ga, gb) + margin > threshold
      end if
    end function crossing_possible

    !> Could the gap have exceeded its largest value so far?
    logical function max_possible(c_, ga, gb, margin)
      integer, intent(in) :: c_
      real(wp), intent(in) :: ga, gb, margin

      ! the last contact's (the lower one's) largest gap is the answer
      max_possible = c_ == k .and. max(ga, gb) + margin &
          > gap_max(1, c_) + tolerance(c_)
    end function max_possible

    !> How far a largest gap may be below the true one.
    real(wp) function tolerance(c_)
      integer, intent(in) :: c_

      tolerance = max_tol * max(abs(gap_max(1, c_)), threshold, &
          tiny(1.0_wp))
    end function tolerance

    !> The crossings and the largest value of gap c over a step that
    !> ended at t_end_ with gap gb, after a flow of span_ (table slot)
    !> from gap ga.  The end rates come from the state at the end, the
    !> one at the start from it flowed back by the table.
    !> The bound b (B_c, or its energy bound) decides cheaply; where it
    !> cannot, the tighter chord bound (chord()) of the segment's modal
    !> amplitudes, and where that cannot either, the searches.
    subroutine watch(c_, ga, gb, span_, slot, t_end_, b)
      integer, intent(in) :: c_, slot
      real(wp), intent(in) :: ga, gb, span_, t_end_, b
      real(wp) :: ends(4), margin

      ends = [ga, gb, 0.0_wp, 0.0_wp]
      margin = -1.0_wp
      amp_now = .false.
      if (crossing_possible(ga, gb, 0.125_wp * b * span_**2)) then
        margin = chord(c_, span_, 0)
        if (crossing_possible(ga, gb, margin)) then
          ends(3:4) = end_rates(c_, slot)
          call find_crossings(c_, span_, t_end_, ends)
        end if
      end if
      if (gb > gap_max(1, c_)) call new_max(c_, gb, t_end_)
      if (ga > gap_max(1, c_)) call new_max(c_, ga, t_end_ - span_)
      if (max_possible(c_, ga, gb, 0.125_wp * b * span_**2)) then
        if (margin < 0.0_wp) margin = chord(c_, span_, 0)
        if (max_possible(c_, ga, gb, margin)) then
          ends(3:4) = end_rates(c_, slot)
          call wait_for_max(c_, max(ga, gb) + margin, span_, t_end_, ends)
        end if
      end if
    end subroutine watch

    !> Amplitudes of the modes in the segment that ends at the current
    !> state (the flow keeps them).
    subroutine segment_amplitudes()
      amp(1:moving) = sqrt(q(1:moving)**2 + (v(1:moving) &
          / p(1:moving))**2)
    end subroutine segment_amplitudes

    !> The largest departure of gap c (order 0) or of its rate (order
    !> 1) from its chord over an interval of length w: mode j departs by
    !> at most min(p_j^2 w^2 / 8, 2) times its amplitude in it, |h_cj|
    !> a_j p_j^order (a_j from segment_amplitudes).
    real(wp) function chord(c_, w, order)
      integer, intent(in) :: c_, order
      real(wp), intent(in) :: w
      integer :: j

      if (.not. amp_now) call segment_amplitudes()
      amp_now = .true.
      chord = 0.0_wp
      do j = 1, moving
        chord = chord + abs(ht(j, c_)) * amp(j) * p(j)**order &
            * min(0.125_wp * (p(j) * w)**2, 2.0_wp)
      end do
    end function chord

    !> Rate of gap c at the step's start (the state flowed back by the
    !> table) and at its end.
    function end_rates(c_, slot) result(rates)
      integer, intent(in) :: c_, slot
      real(wp) :: rates(2)

      rates(1) = dot_product(ht(1:moving, c_), v(1:moving) &
          * tab_c(1:moving, slot) + q(1:moving) * tab_p(1:moving, slot))
      rates(2) = dot_product(ht(1:moving, c_), v(1:moving))
    end function end_rates

    !> Gap c and its rate at tau <= 0 from the state at the step's end
    !> (before any kick there): the exact flow backwards.
    subroutine gap_at(c_, tau, g, d)
      integer, intent(in) :: c_
      real(wp), intent(in) :: tau
      real(wp), intent(out) :: g, d
      real(wp) :: cs(moving), sn(moving)

      counts(3) = counts(3) + 1
      cs = cos(p(1:moving) * tau)
      sn = sin(p(1:moving) * tau)
      g = sum(ht(1:moving, c_) * (q(1:moving) * cs &
          + v(1:moving) / p(1:moving) * sn)) + g_still(c_)
      d = sum(ht(1:moving, c_) * (v(1:moving) * cs &
          - q(1:moving) * p(1:moving) * sn))
    end subroutine gap_at

    !> Every crossing of the threshold by gap c in (-span_, 0], in order.
    !> ends = gap at the start and end, rate at the start and end.
    subroutine find_crossings(c_, span_, t_end_, ends)
      integer, intent(in) :: c_
      real(wp), intent(in) :: span_, t_end_, ends(4)
      real(wp) :: stack(6, max_stack), a, z, fa, fz, da, dz, mid, fm, dm
      real(wp) :: root, margin
      integer :: top

      top = 1
      stack(:, 1) = [-span_, 0.0_wp, ends(1) - threshold, &
          ends(2) - threshold, ends(3), ends(4)]
      do while (top > 0)
        a = stack(1, top)
        z = stack(2, top)
        fa = stack(3, top)
        fz = stack(4, top)
        da = stack(5, top)
        dz = stack(6, top)
        top = top - 1
        margin = chord(c_, z - a, 0)
        if (fa > 0.0_wp .and. fz > 0.0_wp .and. min(fa, fz) - margin &
            > 0.0_wp) cycle
        if (fa <= 0.0_wp .and. fz <= 0.0_wp .and. max(fa, fz) + margin &
            <= 0.0_wp) cycle
        if (((fa > 0.0_wp) .neqv. (fz > 0.0_wp)) .and. &
            monotone(da, dz, chord(c_, z - a, 1))) then
          call refine_root(c_, a, z, fa, root)
          call record(t_end_ + root, merge(-c_, c_, fa > 0.0_wp))
          cycle
        end if
        if (z - a <= 4.0_wp * epsilon(1.0_wp) * abs(t_end_) &
            .or. top + 2 > max_stack) then
          ! a tangency at round-off: a sign change is one crossing
          if ((fa > 0.0_wp) .neqv. (fz > 0.0_wp)) call record( &
              t_end_ + 0.5_wp * (a + z), merge(-c_, c_, fa > 0.0_wp))
          cycle
        end if
        mid = 0.5_wp * (a + z)
        call gap_at(c_, mid, fm, dm)
        fm = fm - threshold
        top = top + 1
        stack(:, top) = [mid, z, fm, fz, dm, dz]
        top = top + 1
        stack(:, top) = [a, mid, fa, fm, da, dm]
      end do
    end subroutine find_crossings

    !> g' keeps one sign on an interval with end rates da, dz, the rate
    !> departing from its chord by at most margin.
    logical function monotone(da, dz, margin)
      real(wp), intent(in) :: da, dz, margin

      monotone = min(da, dz) > margin .or. max(da, dz) < -margin
    end function monotone

    !> The one root of g - threshold in [a, z] (signs differ at the
    !> ends): Newton's method kept inside a shrinking bracket.
    subroutine refine_root(c_, a, z, fa, root)
      integer, intent(in) :: c_
      real(wp), intent(in) :: a, z, fa
      real(wp), intent(out) :: root
      real(wp) :: lo, hi, f, d, trial
      integer :: it
      logical :: rising

      rising = fa <= 0.0_wp
      lo = a
      hi = z
      root = 0.5_wp * (lo + hi)
      do it = 1, 100
        call gap_at(c_, root, f, d)
        f = f - threshold
        if ((f > 0.0_wp) .eqv. rising) then
          hi = root
        else
          lo = root
        end if
        if (hi - lo <= 4.0_wp * epsilon(1.0_wp) * max(abs(t_now), &
            abs(lo))) exit
        trial = root
        if (d /= 0.0_wp) trial = root - f / d
        if (trial <= lo .or. trial >= hi) trial = 0.5_wp * (lo + hi)
        if (abs(trial - root) <= 2.0_wp * epsilon(1.0_wp) &
            * abs(t_now)) then
          root = trial
          exit
        end if
        root = trial
      end do
    end subroutine refine_root

    !> Add a crossing to the table (status_crossings_full if full).
    subroutine record(t_cross, code)
      real(wp), intent(in) :: t_cross
      integer, intent(in) :: code

      if (n_cross >= max_cross) then
        status = status_crossings_full
        return
      end if
      n_cross = n_cross + 1
      crossings(1, n_cross) = t_cross
      crossings(2, n_cross) = real(code, wp)
    end subroutine record

    !> The largest value of gap c in (-span_, 0], to max_tol relative:
    !> branch and bound with the chord bound.
    subroutine find_max(c_, span_, t_end_, ends)
      integer, intent(in) :: c_
      real(wp), intent(in) :: span_, t_end_, ends(4)
      real(wp) :: stack(6, max_stack), a, z, fa, fz, da, dz, mid, fm, dm
      integer :: top

      top = 1
      stack(:, 1) = [-span_, 0.0_wp, ends]
      do while (top > 0)
        a = stack(1, top)
        z = stack(2, top)
        fa = stack(3, top)
        fz = stack(4, top)
        da = stack(5, top)
        dz = stack(6, top)
        top = top - 1
        if (fa > gap_max(1, c_)) call new_max(c_, fa, t_end_ + a)
        if (fz > gap_max(1, c_)) call new_max(c_, fz, t_end_ + z)
        if (max(fa, fz) + chord(c_, z - a, 0) <= gap_max(1, c_) &
            + tolerance(c_)) cycle
        if (monotone(da, dz, chord(c_, z - a, 1))) cycle
        if (top + 2 > max_stack) cycle
        mid = 0.5_wp * (a + z)
        call gap_at(c_, mid, fm, dm)
        top = top + 1
        stack(:, top) = [mid, z, fm, fz, dm, dz]
        top = top + 1
        stack(:, top) = [a, mid, fa, fm, da, dm]
      end do
    end subroutine find_max

    !> A new largest value of gap c, at time when.
    subroutine new_max(c_, value, when)
      integer, intent(in) :: c_
      real(wp), intent(in) :: value, when

      gap_max(1, c_) = value
      gap_max(2, c_) = when
    end subroutine new_max

  end subroutine adaptive

  !> The exact flow of modes 1..nm over a step: (q, v) rotated by the
  !> step's cos, sin / p and p sin (kernels apart, so that they
  !> vectorise: no aliasing between dummy arguments).
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

  !> y += alpha x.
  pure subroutine axpy(nm, alpha, x, y)
    integer, intent(in) :: nm
    real(wp), intent(in) :: alpha, x(nm)
    real(wp), intent(inout) :: y(nm)

    y = y + alpha * x
  end subroutine axpy

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

end module chatter_adaptive
