!> Status codes of the restored core, in one place.
!>
!> The library never stops the program and never prints: every routine
!> that can fail returns one of these codes (0 = ok) and a message.
!> Codes 10-19 come from the card reader, 20-29 from the solver.
module contactsep_status
  use contactsep_kinds, only: wp
  implicit none
  private
  public :: integer_text, real_text

  !> Length of every status message.
  integer, parameter, public :: message_length = 512

  !> Success.
  integer, parameter, public :: status_ok = 0
  !> Card reader: no data set is left (only blank lines remain).
  integer, parameter, public :: status_end_of_deck = 1
  !> An argument is outside its documented range (a caller's mistake).
  integer, parameter, public :: status_bad_argument = 2

  !> A field holds text that its FORMAT cannot read as a number.
  integer, parameter, public :: status_card_not_numeric = 10
  !> A field reads as NaN or Infinity (or overflows the working precision).
  integer, parameter, public :: status_card_not_finite = 11
  !> A line is longer than the 80 columns of a card.
  integer, parameter, public :: status_card_too_long = 12
  !> A line holds a TAB character, which has no column on a card.
  integer, parameter, public :: status_card_has_tab = 13
  !> The deck ends inside a data set (fewer than 6 + 3N cards).
  integer, parameter, public :: status_deck_truncated = 14
  !> Card 5 gives a number of modes N below 1.
  integer, parameter, public :: status_no_modes = 15
  !> N is larger than the caller's max_modes.
  integer, parameter, public :: status_too_many_modes = 16
  !> A line holds a character other than printable ASCII (a stray CR,
  !> a NUL, a form feed, a non-ASCII byte).
  integer, parameter, public :: status_card_not_printable = 17
  !> A value lies outside the range the listing needs (a length that is
  !> not positive, ER outside [0, 1], ...; see contactsep_validation).
  integer, parameter, public :: status_out_of_range = 18

  !> The tip sum at T = 0 is not above DELY: the search has no start.
  integer, parameter, public :: status_release_not_above = 20
  !> T + DELT == T: the impact search cannot advance in this precision.
  integer, parameter, public :: status_search_stalled = 21
  !> The tip sum or DELY is NaN or infinite: no crossing can be found.
  integer, parameter, public :: status_search_not_finite = 22
  !> No impact within max_trace trace lines (the tip may never reach
  !> DELY), or no room for the trace lines of one.
  integer, parameter, public :: status_trace_full = 23
  !> T + DELT does not advance T in the history loop (DELT <= 0 or tiny).
  integer, parameter, public :: status_history_stalled = 24
  !> The history up to TAU needs more than max_history lines.
  integer, parameter, public :: status_history_full = 25
  !> The listing needs more than max_listing bytes.
  integer, parameter, public :: status_listing_full = 26
  !> A work array could not be allocated.
  integer, parameter, public :: status_out_of_memory = 27
  !> An internal WRITE of a listing record failed.
  integer, parameter, public :: status_format_failed = 28

contains

  !> Decimal text of an integer, without blanks, for messages.
  pure function integer_text(value) result(text)
    integer, intent(in) :: value
    character(len=:), allocatable :: text
    character(len=24) :: buffer
    integer :: ios

    write (buffer, '(i0)', iostat=ios) value
    if (ios /= 0) buffer = '?'
    text = trim(buffer)
  end function integer_text

  !> Shortest faithful text of a real (g0), for messages.
  pure function real_text(value) result(text)
    real(wp), intent(in) :: value
    character(len=:), allocatable :: text
    character(len=64) :: buffer
    integer :: ios

    write (buffer, '(g0)', iostat=ios) value
    if (ios /= 0) buffer = '?'
    text = trim(adjustl(buffer))
  end function real_text

end module contactsep_status
