!> Flat interface of the restored core, for f2py.
!>
!> Only scalars and explicit-shape arrays cross it.  Inputs travel in
!> card order:
!>
!>   scalars(18): XL, B, H, RHO, YSTAT, XL2, B2, H2, RHO2,
!>                XL3, B3, H3, RHO3, DELT, ER, DELY, E, XL2C
!>   modes(:, 9): V, C, ALPHA, V2, C2, ALPH2, V3, C3, ALPH3
!>
!> Status 0 is success, 1 the clean end of a deck, anything above an error
!> (the codes are listed in module contactsep_status).  Outputs not
!> reached before an error are zero.
module contactsep_api
  use, intrinsic :: iso_fortran_env, only: int8
  use contactsep_kinds, only: wp
  use contactsep_cards, only: read_cards
  use contactsep_solver, only: data_set, solution, run_data_set
  use contactsep_status, only: status_ok, status_out_of_range, &
      integer_text, real_text
  use contactsep_validation, only: scalar_names, mode_names, requirement, &
      max_history_lines
  implicit none
  private
  public :: read_data_set, solve, take_tables, take_listing

  !> What the last solve produced beyond its numbers, until taken.
  type(solution), save :: kept

  ! The bounds below are literals because f2py must read them from the
  ! declarations: 512 is message_length (status.f90), 18 scalar_count and
  ! 9 mode_column_count (validation.f90).

contains

  !> Read the data set starting at line first_card of the deck text.
  !>
  !> next_card is the line after it.  On an error (status > 1) the
  !> message reads 'card 9, columns 16-30: found ..., expected ...', the
  !> card being the line number in the file; error_card and the columns
  !> give the same place (0 when not applicable, as for a deck that ends
  !> too soon).  The message has no 'data set k' prefix.
  subroutine read_data_set(text, first_line, first_card, blank_zero, &
      max_modes, scalars, n, modes, next_card, status, message, error_card, &
      error_first_column, error_last_column)
    !> The deck file, or the part of it that starts at line first_line.
    character(len=*), intent(in) :: text
    !> Line of the deck file that text starts with (1 for the whole deck).
    integer, intent(in) :: first_line
    !> 1-based line where this data set starts.
    integer, intent(in) :: first_card
    !> 0: blanks in a field are ignored (BN); 1: they are zeros (BZ).
    integer, intent(in) :: blank_zero
    !> Most modes modes has room for.
    integer, intent(in) :: max_modes
    real(wp), intent(out) :: scalars(18)
    integer, intent(out) :: n
    real(wp), intent(out) :: modes(max_modes, 9)
    integer, intent(out) :: next_card
    integer, intent(out) :: status
    character(len=512), intent(out) :: message
    integer, intent(out) :: error_card, error_first_column
    integer, intent(out) :: error_last_column

    call read_cards(text, first_line, first_card, blank_zero, scalars, n, &
        modes, next_card, status, message, error_card, error_first_column, &
        error_last_column)
  end subroutine read_data_set

  !> Run one data set as the listing does.
  !>
  !> The numbers come back at once; the search trace, the history and the
  !> listing text stay here, sized to what the run produced, until
  !> take_tables and take_listing copy them out at exactly that size
  !> (f2py zero-fills every output array, so room for the worst case
  !> would cost time and memory on every call).  max_trace, max_history
  !> and max_listing are limits, not room: pages never written are never
  !> touched.  On an error the tables and the listing hold what came
  !> before it, the listing ending with its last whole line.  The kept
  !> state is one per process: callers serialise solve and the takes.
  subroutine solve(scalars, n, modes, t_end, max_trace, max_history, &
      max_listing, with_listing, p, ape, impact, a1, b1, tip, ty2dt, p2, &
      p3, closing, n_trace, n_history, listing_length, status, message)
    real(wp), intent(in) :: scalars(18)
    !> Number of modes N.
    integer, intent(in) :: n
    real(wp), intent(in) :: modes(n, 9)
    !> End of the lower contact's history (the listing's TAU = 0.060 s).
    real(wp), intent(in) :: t_end
    !> Most trace lines, history lines and listing bytes allowed.
    integer, intent(in) :: max_trace, max_history, max_listing
    !> 0: do not format the listing text (listing_length is 0).
    integer, intent(in) :: with_listing
    !> P(I), APE(I).
    real(wp), intent(out) :: p(n), ape(n)
    !> T, EY, CT, CT2, CT3 (the WRITE after statement 132).
    real(wp), intent(out) :: impact(5)
    !> A1(I), B1(I,1).
    real(wp), intent(out) :: a1(n), b1(n)
    !> Line 315: T, TY, TYDTL, ACT.
    real(wp), intent(out) :: tip(4)
    !> Separator mid-span velocity.
    real(wp), intent(out) :: ty2dt
    real(wp), intent(out) :: p2(n), p3(n)
    !> WM, WM2 (corrected, as printed), WM3, XL2C, GR, BETA, MR1, MR3.
    real(wp), intent(out) :: closing(8)
    !> Lines of the trace and the history, bytes of the listing kept.
    integer, intent(out) :: n_trace, n_history, listing_length
    integer, intent(out) :: status
    character(len=512), intent(out) :: message
    type(data_set) :: inputs
    integer :: i, column, mode
    character(len=:), allocatable :: expected

    call release_kept()
    p = 0.0_wp
    ape = 0.0_wp
    impact = 0.0_wp
    a1 = 0.0_wp
    b1 = 0.0_wp
    tip = 0.0_wp
    ty2dt = 0.0_wp
    p2 = 0.0_wp
    p3 = 0.0_wp
    closing = 0.0_wp
    n_trace = 0
    n_history = 0
    listing_length = 0

    ! A direct call is held to the ranges a deck is.
    status = status_ok
    message = ''
    do i = 1, size(scalars)
      expected = requirement(scalar_names(i), scalars(i))
      if (len(expected) > 0) then
        status = status_out_of_range
        message = trim(scalar_names(i)) // ' = ' // real_text(scalars(i)) &
            // ': expected ' // expected
        return
      end if
    end do
    if (n < 1) then
      status = status_out_of_range
      message = 'N = ' // integer_text(n) // ': expected N >= 1 modes'
      return
    end if
    do column = 1, size(modes, 2)
      do mode = 1, n
        expected = requirement(mode_names(column), modes(mode, column))
        if (len(expected) > 0) then
          status = status_out_of_range
          message = trim(mode_names(column)) // '(' // integer_text(mode) &
              // ') = ' // real_text(modes(mode, column)) &
              // ': expected ' // expected
          return
        end if
      end do
    end do

    if (.not. (t_end > 0.0_wp .and. t_end <= huge(t_end))) then
      status = status_out_of_range
      message = 'TAU = ' // real_text(t_end) // ': expected a positive' &
          // ' end of the history window, s'
      return
    end if
    if (t_end / scalars(14) > real(max_history_lines, wp)) then
      status = status_out_of_range
      message = 'TAU = ' // real_text(t_end) // ': expected at most ' &
          // integer_text(max_history_lines) // ' history lines, TAU/DELT' &
          // ' with DELT = ' // real_text(scalars(14))
      return
    end if

    inputs = data_set(xl=scalars(1), b=scalars(2), h=scalars(3), &
        rho=scalars(4), ystat=scalars(5), xl2=scalars(6), b2=scalars(7), &
        h2=scalars(8), rho2=scalars(9), xl3=scalars(10), b3=scalars(11), &
        h3=scalars(12), rho3=scalars(13), delt=scalars(14), &
        er=scalars(15), dely=scalars(16), e=scalars(17), n=n, &
        xl2c=scalars(18), v=modes(:, 1), c=modes(:, 2), &
        alpha=modes(:, 3), v2=modes(:, 4), c2=modes(:, 5), &
        alph2=modes(:, 6), v3=modes(:, 7), c3=modes(:, 8), &
        alph3=modes(:, 9))
    call run_data_set(inputs, max_trace, max_history, max_listing, kept, &
        status, message, keep_listing=with_listing /= 0, t_end=t_end)

    if (allocated(kept%p)) then
      p = kept%p
      ape = kept%ape
      a1 = kept%a1
      b1 = kept%b1
      p2 = kept%p2
      p3 = kept%p3
      n_trace = kept%n_trace
      n_history = kept%n_history
    end if
    impact = [kept%t_impact, kept%ey, kept%ct, kept%ct2, kept%ct3]
    tip = kept%tip
    ty2dt = kept%ty2dt
    closing = [kept%wm, kept%wm2, kept%wm3, kept%xl2c, kept%gr, &
        kept%beta, kept%mr1, kept%mr3]
    if (with_listing /= 0) listing_length = kept%listing%length
  end subroutine solve

  !> The last solve's trace and history lines, then forgotten here.
  !>
  !> n_trace and n_history are what solve returned (fewer are allowed);
  !> a call without a solve before it gives what is left, or zeros.
  subroutine take_tables(n_trace, n_history, trace_t, trace_ty, &
      trace_tydtl, history_t, history_ty3)
    integer, intent(in) :: n_trace, n_history
    !> Impact-search lines T, TY, TYDTL.
    real(wp), intent(out) :: trace_t(n_trace), trace_ty(n_trace)
    real(wp), intent(out) :: trace_tydtl(n_trace)
    !> History lines T, TY3 up to TAU.
    real(wp), intent(out) :: history_t(n_history), history_ty3(n_history)
    integer :: rows

    trace_t = 0.0_wp
    trace_ty = 0.0_wp
    trace_tydtl = 0.0_wp
    history_t = 0.0_wp
    history_ty3 = 0.0_wp
    if (allocated(kept%trace)) then
      rows = max(0, min(n_trace, kept%n_trace))
      trace_t(1:rows) = kept%trace(1:rows, 1)
      trace_ty(1:rows) = kept%trace(1:rows, 2)
      trace_tydtl(1:rows) = kept%trace(1:rows, 3)
      deallocate (kept%trace)
    end if
    if (allocated(kept%history)) then
      rows = max(0, min(n_history, kept%n_history))
      history_t(1:rows) = kept%history(1:rows, 1)
      history_ty3(1:rows) = kept%history(1:rows, 2)
      deallocate (kept%history)
    end if
  end subroutine take_tables

  !> The last solve's listing text (ASCII bytes, each line ending in LF),
  !> then forgotten here; listing_length as solve returned it.
  subroutine take_listing(listing_length, listing)
    integer, intent(in) :: listing_length
    integer(int8), intent(out) :: listing(listing_length)
    integer :: i, count

    count = 0
    if (allocated(kept%listing%text)) then
      count = max(0, min(listing_length, kept%listing%length))
      do i = 1, count
        listing(i) = int(iachar(kept%listing%text(i:i)), int8)
      end do
      deallocate (kept%listing%text)
    end if
    listing(count + 1:) = 0_int8
  end subroutine take_listing

  !> Forget what the last solve kept.
  subroutine release_kept()
    if (allocated(kept%trace)) deallocate (kept%trace)
    if (allocated(kept%history)) deallocate (kept%history)
    if (allocated(kept%listing%text)) deallocate (kept%listing%text)
  end subroutine release_kept

end module contactsep_api
