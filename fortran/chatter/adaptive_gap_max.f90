!> The search of the adaptive stepper (chatter_adaptive) for the largest
!> value of the last contact's (the lower) gap, to max_tol: branch and
!> bound with the chord bound on the exact flow.  A step whose largest
!> gap may top the running one waits (up to max_waiting of them, with
!> its state) for the end of the run, when the running largest value
!> excludes most of them.
module chatter_adaptive_gap_max
  use contactsep_kinds, only: wp
  use chatter_adaptive_state, only: adaptive_run, head, max_stack, &
      max_tol, max_waiting
  use chatter_adaptive_flow, only: chord, gap_at, monotone
  implicit none
  private
  public :: tolerance, new_max, wait_for_max, search_waiting

contains

  !> How far a largest gap may be below the true one.
  real(wp) function tolerance(run, c)
    type(adaptive_run), intent(in) :: run
    integer, intent(in) :: c

    tolerance = max_tol * max(abs(run%gap_max(1, c)), run%threshold, &
        tiny(1.0_wp))
  end function tolerance

  !> A new largest value of gap c, at time when.
  subroutine new_max(run, c, value, when)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: c
    real(wp), intent(in) :: value, when

    run%gap_max(1, c) = value
    run%gap_max(2, c) = when
  end subroutine new_max

  !> Keep a step whose largest gap may top the running one (upper
  !> bound ub), to be searched at the end; when the table is full, the
  !> step of the lowest bound is searched now instead.
  subroutine wait_for_max(run, c, ub, span, t_end, ends)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: c
    real(wp), intent(in) :: ub, span, t_end, ends(4)
    integer :: low, n

    n = run%n
    if (run%n_waiting < max_waiting) then
      run%n_waiting = run%n_waiting + 1
      low = run%n_waiting
    else
      low = minloc(run%waiting(3, :), 1)
      if (ub <= run%waiting(3, low)) then
        call find_max(run, c, span, t_end, ends)
        return
      end if
      call search_step(run, low)
    end if
    run%waiting(1:8, low) = [t_end, span, ub, ends, real(run%moving, wp)]
    run%waiting(9, low) = run%g_still(c)
    run%waiting(head + 1:head + n, low) = run%q
    run%waiting(head + n + 1:, low) = run%v
  end subroutine wait_for_max

  !> The waiting steps, highest bound first (the running largest gap
  !> grows fastest, and excludes more of the rest).
  subroutine search_waiting(run)
    type(adaptive_run), intent(inout) :: run
    integer :: next

    do while (run%n_waiting > 0)
      next = maxloc(run%waiting(3, 1:run%n_waiting), 1)
      call search_step(run, next)
      run%waiting(:, next) = run%waiting(:, run%n_waiting)
      run%n_waiting = run%n_waiting - 1
    end do
  end subroutine search_waiting

  !> Search waiting step i from its own state (then restore the run's).
  subroutine search_step(run, i)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: i
    real(wp) :: q_run(run%n), v_run(run%n), still_run
    integer :: moving_run, n, k

    n = run%n
    k = run%k
    if (run%waiting(3, i) <= run%gap_max(1, k) + tolerance(run, k)) return
    q_run = run%q
    v_run = run%v
    moving_run = run%moving
    still_run = run%g_still(k)
    run%q(:) = run%waiting(head + 1:head + n, i)
    run%v(:) = run%waiting(head + n + 1:, i)
    run%moving = nint(run%waiting(8, i))
    run%g_still(k) = run%waiting(9, i)
    run%amp_now = .false.
    call find_max(run, k, run%waiting(2, i), run%waiting(1, i), &
        run%waiting(4:7, i))
    run%q(:) = q_run
    run%v(:) = v_run
    run%moving = moving_run
    run%g_still(k) = still_run
    run%amp_now = .false.
  end subroutine search_step

  !> The largest value of gap c in (-span, 0] of the step that ended at
  !> t_end (gaps and rates at its ends in ends), to max_tol relative:
  !> branch and bound with the chord bound.
  subroutine find_max(run, c, span, t_end, ends)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: c
    real(wp), intent(in) :: span, t_end, ends(4)
    real(wp) :: stack(6, max_stack), a, z, fa, fz, da, dz, mid, fm, dm
    integer :: top

    top = 1
    stack(:, 1) = [-span, 0.0_wp, ends]
    do while (top > 0)
      a = stack(1, top)
      z = stack(2, top)
      fa = stack(3, top)
      fz = stack(4, top)
      da = stack(5, top)
      dz = stack(6, top)
      top = top - 1
      if (fa > run%gap_max(1, c)) call new_max(run, c, fa, t_end + a)
      if (fz > run%gap_max(1, c)) call new_max(run, c, fz, t_end + z)
      if (max(fa, fz) + chord(run, c, z - a, 0) <= run%gap_max(1, c) &
          + tolerance(run, c)) cycle
      if (monotone(da, dz, chord(run, c, z - a, 1))) cycle
      if (top + 2 > max_stack) cycle
      mid = 0.5_wp * (a + z)
      call gap_at(run, c, mid, fm, dm)
      top = top + 1
      stack(:, top) = [mid, z, fm, fz, dm, dz]
      top = top + 1
      stack(:, top) = [a, mid, fa, fm, da, dm]
    end do
  end subroutine find_max

end module chatter_adaptive_gap_max
