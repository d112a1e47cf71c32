!> One data set through the steps of Appendix G, in listing order.
!>
!> Release of the contact from YSTAT, search for its first impact on the
!> separator, the impulse, the contact's state after it, the separator's
!> mid-span velocity, the lower contact's tip history to TAU and the
!> closing ratios; each printed as the listing prints it.
!>
!> Dropped from the listing because they never reach the output: the
!> counters NT, NTY and M of statement 115 (and its DELT-0.0005 test,
!> whose branches meet again at 120), K and X of loop 133, and the
!> second index of B1 (always J = 1).
module contactsep_solver
  use, intrinsic :: iso_fortran_env, only: int64
  use contactsep_kinds, only: wp
  use contactsep_status, only: message_length, status_ok, &
      status_bad_argument, status_out_of_memory, integer_text
  use contactsep_beam_properties, only: beam, beam_properties
  use contactsep_modal, only: natural_frequency, release_amplitudes
  use contactsep_impact, only: mode_square_sums, search_first_impact, &
      impulse, post_impact_coefficients, tip_after_impact
  use contactsep_lower_contact, only: corrected_separator_mass, &
      separator_midspan_velocity, lower_contact_history, closing_ratios, &
      tau
  use contactsep_listing, only: listing_text, start_listing, &
      reserve_listing, write_record
  implicit none
  private
  public :: data_set, solution, run_data_set

  !> The listing prints ED = 9.999 to mark the end of the search trace.
  real(wp), parameter :: end_of_trace_mark = 9.999_wp

  !> Inputs of one data set, named as on the cards.
  type :: data_set
    !> Card 1, the contact: length, width, thickness, density (lb/ft^3),
    !> static tip deflection it is released from.
    real(wp) :: xl = 0.0_wp, b = 0.0_wp, h = 0.0_wp, rho = 0.0_wp
    real(wp) :: ystat = 0.0_wp
    !> Card 2, the separator (clamped-clamped).
    real(wp) :: xl2 = 0.0_wp, b2 = 0.0_wp, h2 = 0.0_wp, rho2 = 0.0_wp
    !> Card 3, the lower contact (cantilever).
    real(wp) :: xl3 = 0.0_wp, b3 = 0.0_wp, h3 = 0.0_wp, rho3 = 0.0_wp
    !> Card 4: time step, coefficient of restitution, separator position.
    real(wp) :: delt = 0.0_wp, er = 0.0_wp, dely = 0.0_wp
    !> Card 5: Young's modulus of all three beams and number of modes.
    real(wp) :: e = 0.0_wp
    integer :: n = 0
    !> Card 6: equivalent length of the separator.
    real(wp) :: xl2c = 0.0_wp
    !> Contact modes: eigenvalue kL, tip value X(L), sigma.
    real(wp), allocatable :: v(:), c(:), alpha(:)
    !> Separator modes: kL, mid-span value X(L2/2), sigma.
    real(wp), allocatable :: v2(:), c2(:), alph2(:)
    !> Lower contact modes: kL, tip value X(L3), sigma.
    real(wp), allocatable :: v3(:), c3(:), alph3(:)
  end type data_set

  !> Everything the listing prints for one data set.
  type :: solution
    !> P(I), APE(I): contact frequencies and release amplitudes.
    real(wp), allocatable :: p(:), ape(:)
    !> Search trace lines T, TY, TYDTL: rows 1..n_trace.
    real(wp), allocatable :: trace(:, :)
    integer :: n_trace = 0
    !> Impact time T and impulse EY, with the CT sums.
    real(wp) :: t_impact = 0.0_wp, ey = 0.0_wp
    real(wp) :: ct = 0.0_wp, ct2 = 0.0_wp, ct3 = 0.0_wp
    !> A1(I), B1(I,1): contact motion coefficients at impact.
    real(wp), allocatable :: a1(:), b1(:)
    !> Line 315: T, TY, TYDTL, ACT of the contact after the impact.
    real(wp) :: tip(4) = 0.0_wp
    !> Mid-span velocity of the separator.
    real(wp) :: ty2dt = 0.0_wp
    !> History lines T, TY3: rows 1..n_history.
    real(wp), allocatable :: history(:, :)
    integer :: n_history = 0
    !> Separator and lower contact frequencies P2(I), P3(I).
    real(wp), allocatable :: p2(:), p3(:)
    !> Masses (WM2 after the XL2C correction) and XL2C, as printed.
    real(wp) :: wm = 0.0_wp, wm2 = 0.0_wp, wm3 = 0.0_wp, xl2c = 0.0_wp
    !> Closing ratios GR, BETA, MR1, MR3.
    real(wp) :: gr = 0.0_wp, beta = 0.0_wp, mr1 = 0.0_wp, mr3 = 0.0_wp
    !> The listing text so far.
    type(listing_text) :: listing
  end type solution

contains

  !> Run one data set.  On failure, status /= 0, a message, and result
  !> holds what was computed and listed before the failure.
  !>
  !> max_trace and max_history bound the trace and history lines and
  !> max_listing the bytes of listing text.
  !> keep_listing false skips formatting the text (default true);
  !> t_end ends the history (default the listing's TAU).
  subroutine run_data_set(inputs, max_trace, max_history, max_listing, &
      result, status, message, keep_listing, t_end)
    type(data_set), intent(in) :: inputs
    integer, intent(in) :: max_trace, max_history, max_listing
    logical, intent(in), optional :: keep_listing
    real(wp), intent(in), optional :: t_end
    type(solution), intent(out) :: result
    integer, intent(out) :: status
    character(len=message_length), intent(out) :: message
    type(beam) :: contact, separator, lower
    real(wp) :: ty, tydtl, act, history_end
    integer :: n, i, stat

    status = status_ok
    message = ''
    n = inputs%n
    call check_inputs()
    if (status /= status_ok) return
    allocate (result%p(n), result%ape(n), result%a1(n), result%b1(n), &
        result%p2(n), result%p3(n), result%trace(min(max_trace, 64), 3), &
        result%history(max_history, 2), stat=stat)
    if (stat /= 0) then
      status = status_out_of_memory
      message = 'no memory for the work arrays (max_trace = ' &
          // integer_text(max_trace) // ', max_history = ' &
          // integer_text(max_history) // ')'
      return
    end if
    result%p = 0.0_wp
    result%ape = 0.0_wp
    result%a1 = 0.0_wp
    result%b1 = 0.0_wp
    result%p2 = 0.0_wp
    result%p3 = 0.0_wp
    call start_listing(result%listing, max_listing, keep_listing)
    history_end = tau
    if (present(t_end)) history_end = t_end

    associate (d => inputs, r => result)
      call emit([d%xl2, d%b2, d%h2, d%rho2])
      if (status /= status_ok) return

      contact = beam_properties(d%xl, d%b, d%h, d%rho, d%e)
      separator = beam_properties(d%xl2, d%b2, d%h2, d%rho2, d%e)
      lower = beam_properties(d%xl3, d%b3, d%h3, d%rho3, d%e)
      r%wm = contact%mass
      r%wm3 = lower%mass
      r%xl2c = d%xl2c

      r%p = natural_frequency(contact%w, d%v(1:n), d%xl)
      call release_amplitudes(d%xl, d%ystat, d%v(1:n), d%alpha(1:n), r%ape)
      do i = 1, n
        call emit([d%v(i), d%c(i), d%alpha(i), r%p(i), r%ape(i)])
        if (status /= status_ok) return
      end do

      call mode_square_sums(d%c(1:n), d%c2(1:n), d%c3(1:n), r%ct, r%ct2, &
          r%ct3)
      call search_first_impact(r%ape, d%c(1:n), r%p, d%delt, d%dely, &
          max_trace, r%trace, r%n_trace, r%t_impact, ty, tydtl, act, &
          status, message)
      ! No impact time to report when the search failed.
      if (status /= status_ok) r%t_impact = 0.0_wp
      call reserve_listing(r%listing, bytes_left(r%n_trace))
      call emit_rows(r%trace, r%n_trace)
      if (status /= status_ok) return
      call emit([end_of_trace_mark])
      if (status /= status_ok) return

      ! The impulse uses the separator mass before the XL2C correction.
      r%ey = impulse(d%er, act, r%ct, r%ct2, r%ct3, contact%mass, &
          separator%mass, lower%mass)
      call emit([r%t_impact, r%ey, r%ct, r%ct2, r%ct3])
      if (status /= status_ok) return
      call post_impact_coefficients(r%ape, r%p, r%t_impact, r%a1, r%b1)
      do i = 1, n
        call emit([r%a1(i), r%b1(i)])
        if (status /= status_ok) return
      end do

      ! The listing resets T to 0 and evaluates the state after the
      ! impact there, once.
      r%tip(1) = 0.0_wp
      call tip_after_impact(r%a1, r%b1, d%c(1:n), r%p, r%ey, contact%mass, &
          r%tip(1), r%tip(2), r%tip(3), r%tip(4))
      call emit(r%tip)
      if (status /= status_ok) return

      r%wm2 = corrected_separator_mass(separator%mass, d%xl2c, d%xl2)
      ! P2 from the real length XL2, as in the listing, not from XL2C.
      r%p2 = natural_frequency(separator%w, d%v2(1:n), d%xl2)
      r%p3 = natural_frequency(lower%w, d%v3(1:n), d%xl3)
      r%ty2dt = separator_midspan_velocity(r%ey, r%wm2, d%c2(1:n))
      call emit([r%ty2dt])
      if (status /= status_ok) return

      call lower_contact_history(r%ty2dt, d%c3(1:n), r%p3, d%xl3, d%delt, &
          history_end, r%history, r%n_history, status, message)
      call emit_rows(r%history, r%n_history)
      if (status /= status_ok) return

      do i = 1, n
        call emit([d%v2(i), d%c2(i), d%alph2(i), r%p2(i)])
        if (status /= status_ok) return
      end do
      do i = 1, n
        call emit([d%v3(i), d%c3(i), d%alph3(i), r%p3(i)])
        if (status /= status_ok) return
      end do

      call closing_ratios(d%h2, d%xl2, r%wm, r%wm2, r%wm3, r%gr, r%beta, &
          r%mr1, r%mr3)
      call emit([r%wm, r%wm2, r%wm3, r%xl2c])
      if (status /= status_ok) return
      call emit([r%gr, r%beta, r%mr1, r%mr3])
    end associate

  contains

    subroutine check_inputs()
      if (n < 1) then
        status = status_bad_argument
        message = 'the number of modes N must be 1 or more, not ' &
            // integer_text(n)
      else if (min(max_trace, max_history, max_listing) < 0) then
        status = status_bad_argument
        message = 'max_trace, max_history and max_listing must not be' &
            // ' negative'
      else if (.not. (allocated(inputs%v) .and. allocated(inputs%c) &
          .and. allocated(inputs%alpha) .and. allocated(inputs%v2) &
          .and. allocated(inputs%c2) .and. allocated(inputs%alph2) &
          .and. allocated(inputs%v3) .and. allocated(inputs%c3) &
          .and. allocated(inputs%alph3))) then
        status = status_bad_argument
        message = 'the mode arrays of the data set are not set'
      else if (min(size(inputs%v), size(inputs%c), size(inputs%alpha), &
          size(inputs%v2), size(inputs%c2), size(inputs%alph2), &
          size(inputs%v3), size(inputs%c3), size(inputs%alph3)) < n) then
        status = status_bad_argument
        message = 'the mode arrays hold fewer than N = ' &
            // integer_text(n) // ' modes'
      end if
    end subroutine check_inputs

    !> Bytes of the rest of the listing, from the search trace on, with
    !> the history at its most (max_history lines).
    pure integer function bytes_left(n_trace)
      integer, intent(in) :: n_trace
      integer(int64) :: bytes

      bytes = int(n_trace, int64) * line(3) + line(1) + line(5) &
          + int(n, int64) * line(2) + line(4) + line(1) &
          + int(max_history, int64) * line(2) &
          + 2 * int(n, int64) * line(4) &
          + 2 * line(4)
      bytes_left = int(min(bytes, int(huge(0), int64)))
    end function bytes_left

    !> Bytes of a record of k values (F15.9 each) and its LF.
    pure integer(int64) function line(k)
      integer, intent(in) :: k

      line = 15_int64 * k + 1
    end function line

    !> One WRITE(6,10); on failure, status and message say why.
    subroutine emit(values)
      real(wp), intent(in) :: values(:)
      integer :: write_status
      character(len=message_length) :: write_message

      call write_record(result%listing, values, write_status, write_message)
      if (write_status /= status_ok) then
        status = write_status
        message = write_message
      end if
    end subroutine emit

    !> The first count rows of a trace or history table, one line each;
    !> a failure here comes first in the listing, so it wins.
    subroutine emit_rows(table, count)
      real(wp), intent(in) :: table(:, :)
      integer, intent(in) :: count
      integer :: row, write_status
      character(len=message_length) :: write_message

      do row = 1, count
        call write_record(result%listing, table(row, :), write_status, &
            write_message)
        if (write_status /= status_ok) then
          status = write_status
          message = write_message
          return
        end if
      end do
    end subroutine emit_rows

  end subroutine run_data_set

end module contactsep_solver
