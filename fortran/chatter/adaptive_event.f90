!> The adaptive stepper's stop at its first discontinuity event
!> (chatter_adaptive's stop_open >= 0): a run that only has to answer
!> "is there an event?" need not run the rest of its window.  After
!> each step it reads the step's new crossings in time order, as
!> contactsep.chatter.circuit reads the table (a contact opens at a
!> rising crossing while closed and closes at a falling one while open;
!> the circuit is open while both contacts are), and once an opening of
!> the circuit has lasted stop_open (and more than 0) the run stops:
!> status_stopped_at_event, the step's end recorded as a crossing of
!> code 0, which no contact's intervals read.  It only reads the state:
!> the trajectory up to the stop is the full run's, bit for bit.
module chatter_adaptive_event
  use contactsep_kinds, only: wp
  use chatter_status, only: status_ok, status_stopped_at_event
  use chatter_adaptive_state, only: adaptive_run
  use chatter_adaptive_crossings, only: record
  implicit none
  private
  public :: event_start, event_watch

contains

  !> Watch for an opening of stop_open (s; < 0: never): each contact's
  !> state at the start (its gap above the threshold).
  subroutine event_start(run, stop_open)
    type(adaptive_run), intent(inout) :: run
    real(wp), intent(in) :: stop_open
    integer :: c

    run%stop_open = stop_open
    run%n_read = run%n_cross
    run%circuit_from = -1.0_wp
    do c = 1, run%k
      run%is_open(c) = run%gap(c) > run%threshold
    end do
    if (run%k == 2) then
      if (run%is_open(1) .and. run%is_open(2)) run%circuit_from = 0.0_wp
    end if
  end subroutine event_start

  !> After a step that ended at t_end: its new crossings, both
  !> contacts' merged in time order (each contact's are recorded in
  !> order), then the opening still under way; stop if one lasted.
  !> (t_end from the driver's step count: run%t_now is the Hertz and
  !> flight steps' end only.)
  subroutine event_watch(run, t_end)
    type(adaptive_run), intent(inout) :: run
    real(wp), intent(in) :: t_end
    integer :: next(2), c

    if (run%stop_open < 0.0_wp .or. run%k /= 2) return
    next(1) = unread(run, 1, run%n_read + 1)
    next(2) = unread(run, 2, run%n_read + 1)
    do while (min(next(1), next(2)) <= run%n_cross)
      c = 1
      if (next(1) > run%n_cross) then
        c = 2
      else if (next(2) <= run%n_cross) then
        if (run%crossings(1, next(2)) < run%crossings(1, next(1))) c = 2
      end if
      call cross(run, c, run%crossings(1, next(c)), &
          run%crossings(2, next(c)) > 0.0_wp)
      next(c) = unread(run, c, next(c) + 1)
    end do
    run%n_read = run%n_cross
    if (run%circuit_from >= 0.0_wp) then
      if (lasted(run, t_end)) run%circuit_from = -2.0_wp
    end if
    if (run%circuit_from < -1.5_wp) call stop_here(run, t_end)
  end subroutine event_watch

  !> The first crossing of contact c at or after index i (n_cross + 1:
  !> none).
  integer function unread(run, c, i)
    type(adaptive_run), intent(in) :: run
    integer, intent(in) :: c, i

    unread = i
    do while (unread <= run%n_cross)
      if (nint(abs(run%crossings(2, unread))) == c) return
      unread = unread + 1
    end do
  end function unread

  !> Contact c crosses at time t (opening: rising); an opening of the
  !> circuit that ends here and lasted marks the stop (circuit_from -2).
  subroutine cross(run, c, t, opening)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: c
    real(wp), intent(in) :: t
    logical, intent(in) :: opening

    if (run%circuit_from < -1.5_wp) return
    if (opening .and. .not. run%is_open(c)) then
      run%is_open(c) = .true.
      if (run%is_open(3 - c)) run%circuit_from = t
    else if (.not. opening .and. run%is_open(c)) then
      run%is_open(c) = .false.
      if (run%circuit_from >= 0.0_wp) then
        if (lasted(run, t)) then
          run%circuit_from = -2.0_wp
        else
          run%circuit_from = -1.0_wp
        end if
      end if
    end if
  end subroutine cross

  !> Has the opening under way lasted stop_open by time t?  (The rule
  !> of circuit.discontinuity: length >= min_open, and no zero length.)
  logical function lasted(run, t)
    type(adaptive_run), intent(in) :: run
    real(wp), intent(in) :: t

    lasted = t - run%circuit_from >= run%stop_open &
        .and. t > run%circuit_from
  end function lasted

  !> Stop at the step's end: its time in the table (code 0), the status.
  subroutine stop_here(run, t_end)
    type(adaptive_run), intent(inout) :: run
    real(wp), intent(in) :: t_end

    call record(run, t_end, 0)
    if (run%status == status_ok) run%status = status_stopped_at_event
  end subroutine stop_here

end module chatter_adaptive_event
