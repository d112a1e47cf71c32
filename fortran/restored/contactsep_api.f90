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
  use contactsep_validation, only: scalar_names, mode_names, requirement
  implicit none
  private
  public :: read_data_set, solve

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
  !> trace, history and listing are filled up to n_trace, n_history and
  !> listing_length (ASCII bytes, each line ending in LF); beyond that
  !> they are left as they were, so that room for a long search costs
  !> nothing until it is used.  On an error
  !> they hold what came before it, the listing ending with its last
  !> whole line.
  subroutine solve(scalars, n, modes, max_trace, max_history, max_listing, &
      with_listing, p, ape, trace, n_trace, impact, a1, b1, tip, ty2dt, &
      history, n_history, p2, p3, closing, listing, listing_length, &
      status, message)
    real(wp), intent(in) :: scalars(18)
    !> 0: do not format the listing text (listing_length is 0).
    integer, intent(in) :: with_listing
    !> Number of modes N.
    integer, intent(in) :: n
    !> Most trace lines, history lines and listing bytes there is room for.
    integer, intent(in) :: max_trace, max_history, max_listing
    real(wp), intent(in) :: modes(n, 9)
    !> P(I), APE(I).
    real(wp), intent(out) :: p(n), ape(n)
    !> Impact-search lines T, TY, TYDTL.
    real(wp), intent(out) :: trace(max_trace, 3)
    integer, intent(out) :: n_trace
    !> T, EY, CT, CT2, CT3 (the WRITE after statement 132).
    real(wp), intent(out) :: impact(5)
    !> A1(I), B1(I,1).
    real(wp), intent(out) :: a1(n), b1(n)
    !> Line 315: T, TY, TYDTL, ACT.
    real(wp), intent(out) :: tip(4)
    !> Separator mid-span velocity.
    real(wp), intent(out) :: ty2dt
    !> History lines T, TY3 up to TAU.
    real(wp), intent(out) :: history(max_history, 2)
    integer, intent(out) :: n_history
    real(wp), intent(out) :: p2(n), p3(n)
    !> WM, WM2 (corrected, as printed), WM3, XL2C, GR, BETA, MR1, MR3.
    real(wp), intent(out) :: closing(8)
    !> ASCII bytes of this data set's listing.
    integer(int8), intent(out) :: listing(max_listing)
    integer, intent(out) :: listing_length
    integer, intent(out) :: status
    character(len=512), intent(out) :: message
    type(data_set) :: inputs
    type(solution) :: result
    integer :: i, count, column, mode
    character(len=:), allocatable :: expected

    p = 0.0_wp
    ape = 0.0_wp
    n_trace = 0
    impact = 0.0_wp
    a1 = 0.0_wp
    b1 = 0.0_wp
    tip = 0.0_wp
    ty2dt = 0.0_wp
    n_history = 0
    p2 = 0.0_wp
    p3 = 0.0_wp
    closing = 0.0_wp
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

    inputs = data_set(xl=scalars(1), b=scalars(2), h=scalars(3), &
        rho=scalars(4), ystat=scalars(5), xl2=scalars(6), b2=scalars(7), &
        h2=scalars(8), rho2=scalars(9), xl3=scalars(10), b3=scalars(11), &
        h3=scalars(12), rho3=scalars(13), delt=scalars(14), &
        er=scalars(15), dely=scalars(16), e=scalars(17), n=n, &
        xl2c=scalars(18), v=modes(:, 1), c=modes(:, 2), &
        alpha=modes(:, 3), v2=modes(:, 4), c2=modes(:, 5), &
        alph2=modes(:, 6), v3=modes(:, 7), c3=modes(:, 8), &
        alph3=modes(:, 9))
    call run_data_set(inputs, max_trace, max_history, max_listing, result, &
        status, message, keep_listing=with_listing /= 0)

    if (allocated(result%p)) then
      p = result%p
      ape = result%ape
      a1 = result%a1
      b1 = result%b1
      p2 = result%p2
      p3 = result%p3
      n_trace = result%n_trace
      trace(1:n_trace, :) = result%trace(1:n_trace, :)
      n_history = result%n_history
      history(1:n_history, :) = result%history(1:n_history, :)
    end if
    impact = [result%t_impact, result%ey, result%ct, result%ct2, result%ct3]
    tip = result%tip
    ty2dt = result%ty2dt
    closing = [result%wm, result%wm2, result%wm3, result%xl2c, result%gr, &
        result%beta, result%mr1, result%mr3]
    count = 0
    if (with_listing /= 0) count = result%listing%length
    do i = 1, count
      listing(i) = int(iachar(result%listing%text(i:i)), int8)
    end do
    listing_length = count
  end subroutine solve

end module contactsep_api
