!> First impact of the released contact on the separator, and the state
!> of the contact right after it.
!>
!> The tip of the released contact moves as TY(T) = sum APE(I)*C(I)*
!> COS(P(I)*T).  The listing steps T by DELT while the tip is above the
!> separator (TY > DELY); when a step lands below, it goes back to the
!> last point above (TT) and halves DELT; it stops at a point above once
!> DELT <= 1e-8, or at once when TY == DELY exactly.  Every point above is
!> a trace line.  This module mirrors that loop step for step.
module contactsep_impact
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: iso_fortran_env, only: int64
  use contactsep_kinds, only: wp
  use contactsep_status, only: message_length, status_ok, &
      status_release_not_above, status_search_stalled, &
      status_search_not_finite, status_trace_full, status_out_of_memory, &
      real_text, integer_text
  implicit none
  private
  public :: tip_before_impact, mode_square_sums, search_first_impact
  public :: impulse, post_impact_coefficients, tip_after_impact

  !> The listing's stopping step: the search ends at a point above DELY
  !> once DELT <= 0.00000001.
  real(wp), parameter, public :: smallest_step = 0.00000001_wp

contains

  !> Tip sums of the released contact at time t (loop 90).
  !>
  !> act is the listing's ACT, sum of -P*APE*C: the tip velocity
  !> amplitude without the SIN(P*T) factor.  The listing feeds it to the
  !> impulse as it is; restoring it keeps that.
  pure subroutine tip_before_impact(ape, c, p, t, ty, tydtl, act)
    real(wp), intent(in) :: ape(:), c(:), p(:)
    real(wp), intent(in) :: t
    !> TY: tip displacement; TYDTL: tip velocity; ACT: see above.
    real(wp), intent(out) :: ty, tydtl, act
    real(wp) :: y, ydtl, ac
    integer :: i

    ty = 0.0_wp
    tydtl = 0.0_wp
    act = 0.0_wp
    do i = 1, size(ape)
      y = ape(i) * c(i) * cos(p(i) * t)
      ty = ty + y
      ydtl = -p(i) * ape(i) * c(i) * sin(p(i) * t)
      tydtl = tydtl + ydtl
      ac = -p(i) * ape(i) * c(i)
      act = act + ac
    end do
  end subroutine tip_before_impact

  !> Sums of the squared mode values at the impact points: CT of the
  !> contact tip X(L), CT2 of the separator's mid-span X(L2/2), CT3 of
  !> the lower contact tip.  They weight the masses in the impulse.
  pure subroutine mode_square_sums(c, c2, c3, ct, ct2, ct3)
    real(wp), intent(in) :: c(:), c2(:), c3(:)
    real(wp), intent(out) :: ct, ct2, ct3
    integer :: i

    ct = 0.0_wp
    ct2 = 0.0_wp
    ct3 = 0.0_wp
    do i = 1, size(c)
      ct = ct + c(i)**2
      ct2 = ct2 + c2(i)**2
      ct3 = ct3 + c3(i)**2
    end do
  end subroutine mode_square_sums

  !> The listing's search for the first impact (statements 80-131).
  !>
  !> On success t is the impact time and ty, tydtl, act the tip sums
  !> there; trace(1:n_trace, :) holds the trace lines T, TY, TYDTL.
  !>
  !> The listing loops forever when the tip never comes down to DELY, so
  !> the search fails, keeping the trace so far, when trace has no room
  !> for another line (max_trace is the bound on the search), when
  !> T + DELT == T, or when TY or DELY is not finite.  The last two are
  !> checked only where the listing would take another step, so they
  !> never stop a search that the listing ends.  No bound in time is
  !> used: with DELT close to the period of the first mode the listing
  !> samples the tip too coarsely to see its swing, and it may find its
  !> impact (as the listing prints it) many periods later.
  !>
  !> The listing also starts from an undefined TT when the tip at T = 0
  !> is below DELY; that, and a tip exactly at DELY at T = 0, are
  !> refused: the contact must be released above the separator.
  subroutine search_first_impact(ape, c, p, delt, dely, max_trace, trace, &
      n_trace, t, ty, tydtl, act, status, message)
    real(wp), intent(in) :: ape(:), c(:), p(:)
    !> First step DELT and separator position DELY.
    real(wp), intent(in) :: delt, dely
    !> Most trace lines: the bound on the search.
    integer, intent(in) :: max_trace
    !> Grown (doubled) as lines come, up to max_trace rows: a search of a
    !> few lines does not pay for room for a million.
    real(wp), allocatable, intent(inout) :: trace(:, :)
    integer, intent(out) :: n_trace
    real(wp), intent(out) :: t, ty, tydtl, act
    integer, intent(out) :: status
    character(len=message_length), intent(out) :: message
    real(wp) :: step, tt, difference

    status = status_ok
    message = ''
    n_trace = 0
    step = delt
    t = 0.0_wp
    tt = 0.0_wp
    do
      call tip_before_impact(ape, c, p, t, ty, tydtl, act)
      ! The listing's IF (TY-DELY) 130,131,110, lowered as gfortran does
      ! (<= 0 then < 0), so a NaN goes to 110 as it did there.
      difference = ty - dely
      if (difference < 0.0_wp) then
        if (n_trace == 0) then
          call release_not_above('below')
          return
        end if
        ! Back to the last point above, half the step.
        t = tt
        step = step / 2.0_wp
        t = t + step
      else if (difference <= 0.0_wp) then
        if (n_trace == 0) call release_not_above('exactly at')
        return
      else
        if (n_trace >= size(trace, 1) .and. n_trace < max_trace) &
            call grow_trace()
        if (status /= status_ok) return
        if (n_trace >= size(trace, 1)) then
          status = status_trace_full
          message = 'no impact found within ' &
              // integer_text(max_trace) // ' trace lines (max_trace):' &
              // ' the tip is still above DELY = ' // real_text(dely) &
              // ' at T = ' // real_text(t)
          if (p(1) > 0.0_wp) message = trim(message) // ', ' &
              // real_text(t * p(1) / (2.0_wp * acos(-1.0_wp))) &
              // ' periods of the first mode'
          ! Either cause is the deck's: say both.
          message = trim(message) // ' (either the tip never reaches' &
              // ' DELY, or DELT is too small to get there in that many' &
              // ' steps)'
          return
        end if
        n_trace = n_trace + 1
        trace(n_trace, :) = [t, ty, tydtl]
        ! IF (DELT-0.00000001) 131,131,122
        if (step - smallest_step <= 0.0_wp) return
        if (.not. (ieee_is_finite(ty) .and. ieee_is_finite(dely))) then
          status = status_search_not_finite
          message = 'the tip sum TY is ' // real_text(ty) // ' at T = ' &
              // real_text(t) // ' and the separator is at DELY = ' &
              // real_text(dely) // ': no impact can be found (the modal' &
              // ' sums overflow: too many modes, or k_jL too large, for' &
              // ' this precision)'
          return
        end if
        if (.not. (t + step > t)) then
          status = status_search_stalled
          message = 'the impact search cannot advance: T + DELT == T at T' &
              // ' = ' // real_text(t) // ' with DELT = ' // real_text(step) &
              // ' in this precision'
          return
        end if
        tt = t
        t = t + step
      end if
    end do

  contains

    !> Double the trace's rows (at most max_trace), keeping its lines.
    subroutine grow_trace()
      real(wp), allocatable :: grown(:, :)
      integer :: rows, stat

      rows = int(min(int(max_trace, int64), &
          max(64_int64, 2_int64 * size(trace, 1))))
      allocate (grown(rows, 3), stat=stat)
      if (stat /= 0) then
        status = status_out_of_memory
        message = 'no memory for ' // integer_text(rows) // ' trace lines'
        return
      end if
      grown(1:n_trace, :) = trace(1:n_trace, :)
      call move_alloc(grown, trace)
    end subroutine grow_trace

    subroutine release_not_above(relation)
      character(len=*), intent(in) :: relation

      status = status_release_not_above
      message = 'the released tip TY = ' // real_text(ty) // ' at T = 0' &
          // ' (the modal sum for YSTAT) is ' // relation &
          // ' the separator DELY = ' // real_text(dely) &
          // ': the impact search must start above it'
    end subroutine release_not_above

  end subroutine search_first_impact

  !> Impulse EY of the impact (statement 132), with restitution er.
  !>
  !> wm2 is the separator mass before the XL2C correction, as the listing
  !> has it at this point.
  pure function impulse(er, act, ct, ct2, ct3, wm, wm2, wm3) result(ey)
    real(wp), intent(in) :: er, act, ct, ct2, ct3, wm, wm2, wm3
    real(wp) :: ey

    ey = ((1.0_wp + er) * act) / ((ct / wm) + (ct2 / wm2) + (ct3 / wm3))
  end function impulse

  !> Coefficients A1(I) and B1(I,1) of the contact's motion at impact
  !> time t (loop 133).
  pure subroutine post_impact_coefficients(ape, p, t, a1, b1)
    real(wp), intent(in) :: ape(:), p(:)
    real(wp), intent(in) :: t
    real(wp), intent(out) :: a1(:), b1(:)
    integer :: i

    do i = 1, size(ape)
      a1(i) = ape(i) * cos(p(i) * t)
      b1(i) = -ape(i) * sin(p(i) * t)
    end do
  end subroutine post_impact_coefficients

  !> Tip sums of the contact after an impulse ey, at time t from the
  !> impact (loop 240; the listing evaluates them at T = 0 only).
  pure subroutine tip_after_impact(a1, b1, c, p, ey, wm, t, ty, tydtl, act)
    real(wp), intent(in) :: a1(:), b1(:), c(:), p(:)
    !> Impulse EY and contact mass WM.
    real(wp), intent(in) :: ey, wm
    real(wp), intent(in) :: t
    real(wp), intent(out) :: ty, tydtl, act
    real(wp) :: y, ydtl, ac
    integer :: i

    ty = 0.0_wp
    tydtl = 0.0_wp
    act = 0.0_wp
    do i = 1, size(a1)
      y = a1(i) * cos(p(i) * t)
      y = (y + (b1(i) - ((ey * c(i)) / (wm * p(i)))) * sin(p(i) * t)) * c(i)
      ty = ty + y
      ydtl = -a1(i) * (sin(p(i) * t))
      ydtl = (ydtl + (b1(i) - ((ey * c(i)) / (wm * p(i)))) &
          * cos(p(i) * t)) * c(i) * p(i)
      tydtl = tydtl + ydtl
      ac = p(i) * b1(i) * c(i)
      act = act + ac
    end do
  end subroutine tip_after_impact

end module contactsep_impact
