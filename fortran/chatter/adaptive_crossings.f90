!> What the adaptive stepper (chatter_adaptive) watches over each step:
!> the crossings of the open threshold by the gaps, found by bisection
!> on the exact flow and refined by Newton's method, and the steps whose
!> largest lower gap may top the running one (for
!> chatter_adaptive_gap_max).  Cheap bounds decide first: the energy
!> bound, then B_c, then the chord bound of the segment's amplitudes;
!> only where none can, the searches.
module chatter_adaptive_crossings
  use contactsep_kinds, only: wp
  use chatter_status, only: status_crossings_full, status_energy_bound
  use chatter_adaptive_state, only: adaptive_run, max_stack
  use chatter_adaptive_flow, only: amplitude_bounds, chord, end_rates, &
      gap_at, monotone, energy
  use chatter_adaptive_gap_max, only: new_max, tolerance, wait_for_max
  implicit none
  private
  public :: watch, watch_fixed, watch_grid, record

contains

  !> The static correction's fixed steps with a force at either end:
  !> the physical gaps (modal + C lambda) are known at the grid points
  !> only (the series springs' displacement follows the forces, which
  !> the splitting applies there), so a crossing is placed by linear
  !> interpolation between them and the largest gap taken among them,
  !> as the fixed-step stepper's samples at every step are.  ga, gb: the
  !> physical gaps at the step's start and end (t_end).
  subroutine watch_grid(run, ga, gb, t_end)
    type(adaptive_run), intent(inout) :: run
    real(wp), intent(in) :: ga(run%k), gb(run%k), t_end
    real(wp) :: fa, fb
    integer :: c

    do c = 1, run%k
      fa = ga(c) - run%threshold
      fb = gb(c) - run%threshold
      if ((fa > 0.0_wp) .neqv. (fb > 0.0_wp)) call record(run, &
          t_end - run%dt + run%dt * fa / (fa - fb), &
          merge(-c, c, fa > 0.0_wp))
      if (c == run%k .and. gb(c) > run%gap_max(1, c)) &
          call new_max(run, c, gb(c), t_end)
    end do
  end subroutine watch_grid

  !> watch() of every contact over a fixed step's flow: the energy
  !> bound first (free), the amplitudes if need be.  Every bound here
  !> assumes the energy within run%energy_bound: a step that took it
  !> past (a kick of a step too coarse for the contact; energy() is
  !> cached between kicks) or made it not a number stops the run with
  !> status_energy_bound before any search (issue 31: a blown-up state
  !> sent the crossings' bisection down an endless tree).
  subroutine watch_fixed(run, span, slot, t_end)
    type(adaptive_run), intent(inout) :: run
    real(wp), intent(in) :: span, t_end
    integer, intent(in) :: slot
    real(wp) :: margin, e_now
    integer :: j

    call energy(run, e_now)
    if (.not. e_now <= run%energy_bound) then
      run%status = status_energy_bound
      return
    end if
    do j = 1, run%k
      margin = 0.125_wp * run%energy_b(j) * span**2
      if (crossing_possible(run, run%gap(j), run%gap_new(j), margin) &
          .or. max_possible(run, j, run%gap(j), run%gap_new(j), &
          margin)) then
        call amplitude_bounds(run)
        call watch(run, j, run%gap(j), run%gap_new(j), span, slot, &
            t_end, run%bound(j))
      end if
    end do
  end subroutine watch_fixed

  !> The crossings and the largest value of gap c over a step that
  !> ended at t_end with gap gb, after a flow of span (table slot)
  !> from gap ga.  The end rates come from the state at the end, the
  !> one at the start from it flowed back by the table.
  !> The bound b (B_c, or its energy bound) decides cheaply; where it
  !> cannot, the tighter chord bound (chord()) of the segment's modal
  !> amplitudes, and where that cannot either, the searches.
  subroutine watch(run, c, ga, gb, span, slot, t_end, b)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: c, slot
    real(wp), intent(in) :: ga, gb, span, t_end, b
    real(wp) :: ends(4), margin

    ends = [ga, gb, 0.0_wp, 0.0_wp]
    margin = -1.0_wp
    run%amp_now = .false.
    if (crossing_possible(run, ga, gb, 0.125_wp * b * span**2)) then
      margin = chord(run, c, span, 0)
      if (crossing_possible(run, ga, gb, margin)) then
        ends(3:4) = end_rates(run, c, slot)
        call find_crossings(run, c, span, t_end, ends)
      end if
    end if
    if (gb > run%gap_max(1, c)) call new_max(run, c, gb, t_end)
    if (ga > run%gap_max(1, c)) call new_max(run, c, ga, t_end - span)
    if (max_possible(run, c, ga, gb, 0.125_wp * b * span**2)) then
      if (margin < 0.0_wp) margin = chord(run, c, span, 0)
      if (max_possible(run, c, ga, gb, margin)) then
        ends(3:4) = end_rates(run, c, slot)
        call wait_for_max(run, c, max(ga, gb) + margin, span, t_end, &
            ends)
      end if
    end if
  end subroutine watch

  !> Could the gap have crossed the threshold within the step?
  !> (Both use a bound of the gap's departure from its chord.)
  logical function crossing_possible(run, ga, gb, margin)
    type(adaptive_run), intent(in) :: run
    real(wp), intent(in) :: ga, gb, margin

    if ((ga > run%threshold) .neqv. (gb > run%threshold)) then
      crossing_possible = .true.
    else if (ga > run%threshold) then
      crossing_possible = min(ga, gb) - margin <= run%threshold
    else
      crossing_possible = max(ga, gb) + margin > run%threshold
    end if
  end function crossing_possible

  !> Could the gap have exceeded its largest value so far?
  logical function max_possible(run, c, ga, gb, margin)
    type(adaptive_run), intent(in) :: run
    integer, intent(in) :: c
    real(wp), intent(in) :: ga, gb, margin

    ! the last contact's (the lower one's) largest gap is the answer
    max_possible = c == run%k .and. max(ga, gb) + margin &
        > run%gap_max(1, c) + tolerance(run, c)
  end function max_possible

  !> Every crossing of the threshold by gap c in (-span, 0], in order.
  !> ends = gap at the start and end, rate at the start and end.
  subroutine find_crossings(run, c, span, t_end, ends)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: c
    real(wp), intent(in) :: span, t_end, ends(4)
    real(wp) :: stack(6, max_stack), a, z, fa, fz, da, dz, mid, fm, dm
    real(wp) :: root, margin, threshold
    integer :: top

    threshold = run%threshold
    top = 1
    stack(:, 1) = [-span, 0.0_wp, ends(1) - threshold, &
        ends(2) - threshold, ends(3), ends(4)]
    do while (top > 0)
      a = stack(1, top)
      z = stack(2, top)
      fa = stack(3, top)
      fz = stack(4, top)
      da = stack(5, top)
      dz = stack(6, top)
      top = top - 1
      margin = chord(run, c, z - a, 0)
      if (fa > 0.0_wp .and. fz > 0.0_wp .and. min(fa, fz) - margin &
          > 0.0_wp) cycle
      if (fa <= 0.0_wp .and. fz <= 0.0_wp .and. max(fa, fz) + margin &
          <= 0.0_wp) cycle
      if (((fa > 0.0_wp) .neqv. (fz > 0.0_wp)) .and. &
          monotone(da, dz, chord(run, c, z - a, 1))) then
        call refine_root(run, c, a, z, fa, root)
        call record(run, t_end + root, merge(-c, c, fa > 0.0_wp))
        cycle
      end if
      if (z - a <= 4.0_wp * epsilon(1.0_wp) * abs(t_end) &
          .or. top + 2 > max_stack) then
        ! a tangency at round-off: a sign change is one crossing
        if ((fa > 0.0_wp) .neqv. (fz > 0.0_wp)) call record(run, &
            t_end + 0.5_wp * (a + z), merge(-c, c, fa > 0.0_wp))
        cycle
      end if
      mid = 0.5_wp * (a + z)
      call gap_at(run, c, mid, fm, dm)
      fm = fm - threshold
      top = top + 1
      stack(:, top) = [mid, z, fm, fz, dm, dz]
      top = top + 1
      stack(:, top) = [a, mid, fa, fm, da, dm]
    end do
  end subroutine find_crossings

  !> The one root of g - threshold in [a, z] (signs differ at the
  !> ends): Newton's method kept inside a shrinking bracket.
  subroutine refine_root(run, c, a, z, fa, root)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: c
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
      call gap_at(run, c, root, f, d)
      f = f - run%threshold
      if ((f > 0.0_wp) .eqv. rising) then
        hi = root
      else
        lo = root
      end if
      if (hi - lo <= 4.0_wp * epsilon(1.0_wp) * max(abs(run%t_now), &
          abs(lo))) exit
      trial = root
      if (d /= 0.0_wp) trial = root - f / d
      if (trial <= lo .or. trial >= hi) trial = 0.5_wp * (lo + hi)
      if (abs(trial - root) <= 2.0_wp * epsilon(1.0_wp) &
          * abs(run%t_now)) then
        root = trial
        exit
      end if
      root = trial
    end do
  end subroutine refine_root

  !> Add a crossing to the table (status_crossings_full if full).
  subroutine record(run, t_cross, code)
    type(adaptive_run), intent(inout) :: run
    real(wp), intent(in) :: t_cross
    integer, intent(in) :: code

    if (run%n_cross >= run%max_cross) then
      run%status = status_crossings_full
      return
    end if
    run%n_cross = run%n_cross + 1
    run%crossings(1, run%n_cross) = t_cross
    run%crossings(2, run%n_cross) = real(code, wp)
  end subroutine record

end module chatter_adaptive_crossings
