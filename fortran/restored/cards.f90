!> Card-image reader for the decks of Appendix G.
!>
!> A deck is text with one card per line (LF separated; one trailing CR is
!> dropped, so CRLF decks read the same).  A data set is 6 + 3N cards,
!> each read with an internal READ in the listing's own formats, so the
!> numbers are bit for bit what the original READ(5,10) produces:
!>
!>   card 1   XL, B, H, RHO, YSTAT      FORMAT 10 (7F15.9)
!>   card 2   XL2, B2, H2, RHO2         FORMAT 10
!>   card 3   XL3, B3, H3, RHO3         FORMAT 10
!>   card 4   DELT, ER, DELY            FORMAT 10
!>   card 5   E, N                      FORMAT 15 (E15.9,I2)
!>   card 6   XL2C                      FORMAT 10
!>   N cards  V, C, ALPHA               FORMAT 10
!>   N cards  V2, C2, ALPH2             FORMAT 10
!>   N cards  V3, C3, ALPH3             FORMAT 10
!>
!> Fields sit in fixed columns (1-15, 16-30, ...; N in 16-17); a field
!> without a decimal point has an implied one (F15.9: '19' is 19e-9).
!> Short lines are padded with blanks to 80 columns.  Blanks inside a
!> field are ignored (BN, what gfortran does on stdin) or read as zeros
!> (BZ, what the card readers of the day did).  Columns a card's READ does
!> not reach are ignored, as in the original program.
!>
!> Blank lines are cards (of zeros) inside a data set, as they were for
!> the original program.  When only blank lines remain where a data set
!> would start, the deck has ended cleanly (status_end_of_deck): trailing
!> blank lines are ignored.
!>
!> Refused, naming the line, columns, text found and what was expected:
!> a field gfortran cannot read, NaN or Infinity (also an overflow in the
!> working precision), a line over 80 columns, a TAB or other character
!> outside printable ASCII, N < 1, N above the caller's room, and a deck
!> ending inside a data set.  Values gfortran does read (a field cut short
!> by a comma, say) are taken as the original program takes them.
module contactsep_cards
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use contactsep_kinds, only: wp
  use contactsep_status, only: message_length, status_ok, &
      status_end_of_deck, status_bad_argument, status_card_not_numeric, &
      status_card_not_finite, status_card_too_long, status_card_has_tab, &
      status_deck_truncated, status_no_modes, status_too_many_modes, &
      status_card_not_printable, status_out_of_range, integer_text
  use contactsep_validation, only: card_scalar_count => scalar_count, &
      mode_column_count, scalar_names, mode_names, requirement
  implicit none
  private
  public :: read_cards

  !> Columns of a punched card.
  integer, parameter :: card_width = 80

  !> Width of an F15.9 / E15.9 field.
  integer, parameter :: field_width = 15
  character(len=*), parameter :: tab = achar(9), carriage_return = achar(13)
  character(len=*), parameter :: line_feed = achar(10)

  !> Numbers read from each of cards 1-6 (card 5's N is read apart).
  integer, parameter :: reals_on_card(6) = [5, 4, 4, 3, 1, 1]

  !> Where a failing field is, for the caller's error report.
  type :: card_error
    integer :: card = 0
    integer :: first_column = 0
    integer :: last_column = 0
  end type card_error

contains

  !> Read the data set whose first card is line first_card of the deck.
  !>
  !> text may be the whole deck (first_line = 1) or a part of it whose
  !> first line is line first_line of the deck file: card numbers in
  !> messages are always those of the file.
  !>
  !> scalars receives cards 1-6 in card order (card_scalar_count values,
  !> N excluded); modes(i, :) receives mode i's three cards.  next_card is
  !> the line after the data set.  Status 1 means no data set is left;
  !> on an error (status > 1) error_card and the columns point at the
  !> offending field (0 when not applicable) and the message names the
  !> card, the columns, the text found and what was expected.
  subroutine read_cards(text, first_line, first_card, blank_zero, scalars, &
      n, modes, next_card, status, message, error_card, error_first_column, &
      error_last_column)
    !> The whole deck.
    character(len=*), intent(in) :: text
    !> Line of the deck file that text starts with.
    integer, intent(in) :: first_line
    !> 1-based line where this data set starts.
    integer, intent(in) :: first_card
    !> 0: blanks in a field are ignored (BN); 1: blanks are zeros (BZ).
    integer, intent(in) :: blank_zero
    real(wp), intent(out) :: scalars(:)
    integer, intent(out) :: n
    !> size(modes, 1) is the most modes the caller has room for.
    real(wp), intent(out) :: modes(:, :)
    integer, intent(out) :: next_card
    integer, intent(out) :: status
    character(len=message_length), intent(out) :: message
    integer, intent(out) :: error_card, error_first_column
    integer, intent(out) :: error_last_column

    character(len=card_width) :: card
    character(len=2) :: blank
    type(card_error) :: location
    integer :: position, line, k, first, mode, group, total_lines, found

    scalars = 0.0_wp
    modes = 0.0_wp
    n = 0
    next_card = first_card
    status = status_ok
    message = ''
    location = card_error()

    if (first_line < 1 .or. first_card < first_line) then
      call fail(status_bad_argument, 'need 1 <= first_line <= first_card,' &
          // ' not ' // integer_text(first_line) // ' and ' &
          // integer_text(first_card))
      return
    end if
    if (blank_zero /= 0 .and. blank_zero /= 1) then
      call fail(status_bad_argument, 'blank_zero must be 0 (BN) or 1 (BZ),' &
          // ' not ' // integer_text(blank_zero))
      return
    end if
    if (size(scalars) < card_scalar_count .or. &
        size(modes, 2) < mode_column_count) then
      call fail(status_bad_argument, 'scalars or modes has too few columns')
      return
    end if
    blank = 'BN'
    if (blank_zero == 1) blank = 'BZ'

    ! Walk to the first card of the data set.
    position = 1
    line = first_line
    do while (line < first_card .and. position <= len(text))
      call skip_line(text, position)
      line = line + 1
    end do
    total_lines = line - 1 + lines_from(text, position)
    if (only_blank_lines(text, position)) then
      next_card = max(first_card, total_lines + 1)
      call fail(status_end_of_deck, 'no data set is left (the deck ends' &
          // ' at card ' // integer_text(total_lines) // ')')
      return
    end if

    first = 0
    do k = 1, 6
      if (position > len(text)) then
        call fail(status_deck_truncated, 'expected 6 + 3N cards (N is on' &
            // ' card 5 of the data set), found ' // integer_text(k - 1) &
            // ' (the deck ends at card ' // integer_text(total_lines) &
            // ', inside the data set that starts at card ' &
            // integer_text(first_card) // ')')
        return
      end if
      call next_card_image(text, position, line, card, location, status, &
          message)
      if (status /= status_ok) then
        call report_where()
        return
      end if
      if (k == 5) then
        call read_card5(card, line, blank, scalars(first + 1), n, location, &
            status, message)
      else
        call read_reals(card, line, blank, &
            scalar_names(first + 1:first + reals_on_card(k)), &
            scalars(first + 1:first + reals_on_card(k)), location, status, &
            message)
      end if
      if (status /= status_ok) then
        call report_where()
        return
      end if
      first = first + reals_on_card(k)
      line = line + 1
    end do

    found = total_lines - first_card + 1
    if (found < 6 + 3 * n) then
      call fail(status_deck_truncated, 'expected 6 + 3N = ' &
          // integer_text(6 + 3 * n) // ' cards, found ' &
          // integer_text(found) // ' (N = ' // integer_text(n) &
          // ' on card ' // integer_text(first_card + 4) &
          // '; the deck ends at card ' // integer_text(total_lines) // ')')
      return
    end if
    if (n > size(modes, 1)) then
      location = card_error(first_card + 4, 16, 17)
      call fail(status_too_many_modes, 'card ' &
          // integer_text(first_card + 4) // ', columns 16-17: found N = ' &
          // integer_text(n) // ', expected at most ' &
          // integer_text(size(modes, 1)) &
          // ' modes (max_modes, the room the caller gave)')
      return
    end if

    do group = 1, 3
      do mode = 1, n
        call next_card_image(text, position, line, card, location, status, &
            message)
        if (status /= status_ok) then
          call report_where()
          return
        end if
        call read_reals(card, line, blank, &
            mode_names(3 * group - 2:3 * group), &
            modes(mode, 3 * group - 2:3 * group), location, status, message, &
            mode)
        if (status /= status_ok) then
          call report_where()
          return
        end if
        line = line + 1
      end do
    end do
    next_card = line

  contains

    subroutine fail(code, text_of_error)
      integer, intent(in) :: code
      character(len=*), intent(in) :: text_of_error

      status = code
      message = text_of_error
      call report_where()
    end subroutine fail

    subroutine report_where()
      error_card = location%card
      error_first_column = location%first_column
      error_last_column = location%last_column
    end subroutine report_where

  end subroutine read_cards

  !> Move position past the end of the current line.
  subroutine skip_line(text, position)
    character(len=*), intent(in) :: text
    integer, intent(inout) :: position
    integer :: lf

    lf = index(text(position:), line_feed)
    if (lf == 0) then
      position = len(text) + 1
    else
      position = position + lf
    end if
  end subroutine skip_line

  !> Bounds of the line starting at position, without its LF and one CR.
  subroutine line_bounds(text, position, first, last)
    character(len=*), intent(in) :: text
    integer, intent(in) :: position
    integer, intent(out) :: first, last
    integer :: lf

    first = position
    lf = index(text(position:), line_feed)
    if (lf == 0) then
      last = len(text)
    else
      last = position + lf - 2
    end if
    if (last >= first) then
      if (text(last:last) == carriage_return) last = last - 1
    end if
  end subroutine line_bounds

  !> Number of lines from position to the end of the text.
  pure function lines_from(text, position) result(count)
    character(len=*), intent(in) :: text
    integer, intent(in) :: position
    integer :: count, i

    count = 0
    if (position > len(text)) return
    do i = position, len(text)
      if (text(i:i) == line_feed) count = count + 1
    end do
    ! A last line without its LF still counts.
    if (text(len(text):len(text)) /= line_feed) count = count + 1
  end function lines_from

  !> Whether every line from position on is empty or spaces only.
  function only_blank_lines(text, position) result(blank)
    character(len=*), intent(in) :: text
    integer, intent(in) :: position
    logical :: blank
    integer :: at, first, last

    blank = .true.
    at = position
    do while (at <= len(text))
      call line_bounds(text, at, first, last)
      if (last >= first) then
        if (len_trim(text(first:last)) > 0) then
          blank = .false.
          return
        end if
      end if
      call skip_line(text, at)
    end do
  end function only_blank_lines

  !> Take the line at position as a card image of 80 columns.
  !>
  !> Rejects lines longer than a card, TAB characters (whose column on a
  !> card would be a guess) and any other character a card cannot hold:
  !> gfortran would end a record at a stray CR, or fail on a NUL, and the
  !> columns after it would no longer be those of the card.
  subroutine next_card_image(text, position, line, card, location, status, &
      message)
    character(len=*), intent(in) :: text
    integer, intent(inout) :: position
    integer, intent(in) :: line
    character(len=card_width), intent(out) :: card
    type(card_error), intent(out) :: location
    integer, intent(out) :: status
    character(len=message_length), intent(out) :: message
    integer :: first, last, width, tab_column, column, code

    status = status_ok
    message = ''
    card = ''
    call line_bounds(text, position, first, last)
    call skip_line(text, position)
    width = last - first + 1
    if (width > card_width) then
      location = card_error(line, card_width + 1, width)
      status = status_card_too_long
      message = 'card ' // integer_text(line) // ', columns ' &
          // integer_text(card_width + 1) // '-' // integer_text(width) &
          // ': found ''' // text(first + card_width:min(last, first &
          + card_width + 39)) // ''', expected nothing past column 80' &
          // ' (a card has 80 columns)'
      return
    end if
    if (width <= 0) return
    tab_column = index(text(first:last), tab)
    if (tab_column > 0) then
      location = card_error(line, tab_column, tab_column)
      status = status_card_has_tab
      message = 'card ' // integer_text(line) // ', column ' &
          // integer_text(tab_column) // ': found a TAB, expected a blank' &
          // ' (a TAB has no fixed column on a card)'
      return
    end if
    do column = 1, width
      code = iachar(text(first + column - 1:first + column - 1))
      if (code < 32 .or. code > 126) then
        location = card_error(line, column, column)
        status = status_card_not_printable
        message = 'card ' // integer_text(line) // ', column ' &
            // integer_text(column) // ': found the character of code ' &
            // integer_text(code) // ', expected a printable ASCII' &
            // ' character (a card ends at LF or CR LF)'
        return
      end if
    end do
    card = text(first:last)
  end subroutine next_card_image

  !> Read the leading values of a FORMAT 10 card, checking each field.
  subroutine read_reals(card, line, blank, names, values, location, status, &
      message, mode)
    character(len=card_width), intent(in) :: card
    integer, intent(in) :: line
    !> 'BN' or 'BZ': how blanks inside a field read.
    character(len=2), intent(in) :: blank
    !> Listing names of the values, for messages.
    character(len=*), intent(in) :: names(:)
    real(wp), intent(out) :: values(:)
    type(card_error), intent(out) :: location
    integer, intent(out) :: status
    character(len=message_length), intent(out) :: message
    !> Mode number, present on mode cards (names then get '(mode)').
    integer, intent(in), optional :: mode
    character(len=:), allocatable :: label, real_format, expected
    integer :: ios, field, first_column
    character(len=message_length) :: io_message

    status = status_ok
    message = ''
    location = card_error()
    values = 0.0_wp
    ! FORMAT 10 of the listing, with the blank mode made explicit.
    real_format = '(' // blank // ',7F15.9)'
    read (card, real_format, iostat=ios, iomsg=io_message) values
    if (ios == 0) then
      do field = 1, size(values)
        if (.not. ieee_is_finite(values(field))) then
          call field_error(field, status_card_not_finite, &
              'expected a finite number', &
              ' (NaN, Infinity or beyond the range of this precision)')
          return
        end if
        expected = requirement(names(field), values(field))
        if (len(expected) > 0) then
          call field_error(field, status_out_of_range, &
              'expected ' // expected, '')
          return
        end if
      end do
      return
    end if
    ! Locate the field the READ stumbled on by reading one at a time.
    do field = 1, size(values)
      first_column = (field - 1) * field_width + 1
      read (card(first_column:first_column + field_width - 1), &
          real_format, iostat=ios) values(field)
      if (ios /= 0) then
        call field_error(field, status_card_not_numeric, &
            'expected a number', '')
        return
      end if
    end do
    location = card_error(line, 1, size(values) * field_width)
    status = status_card_not_numeric
    message = 'card ' // integer_text(line) // ': found a card that' &
        // ' FORMAT 10 (7F15.9) cannot read (' // trim(io_message) &
        // '), expected numbers in columns 1-15, 16-30, ...'

  contains

    subroutine field_error(field, code, expectation, reason)
      integer, intent(in) :: field, code
      character(len=*), intent(in) :: expectation, reason
      integer :: c1, c2

      c1 = (field - 1) * field_width + 1
      c2 = c1 + field_width - 1
      label = trim(names(field))
      if (present(mode)) label = label // '(' // integer_text(mode) // ')'
      location = card_error(line, c1, c2)
      status = code
      message = 'card ' // integer_text(line) // ', columns ' &
          // integer_text(c1) // '-' // integer_text(c2) // ': found ' &
          // quoted(card(c1:c2)) // ', ' // expectation // ' (' // label &
          // ', F15.9)' // reason
    end subroutine field_error

  end subroutine read_reals

  !> Read card 5, FORMAT 15 (E15.9,I2): Young's modulus E and N.
  subroutine read_card5(card, line, blank, e, n, location, status, message)
    character(len=card_width), intent(in) :: card
    integer, intent(in) :: line
    !> 'BN' or 'BZ': how blanks inside a field read.
    character(len=2), intent(in) :: blank
    real(wp), intent(out) :: e
    integer, intent(out) :: n
    type(card_error), intent(out) :: location
    integer, intent(out) :: status
    character(len=message_length), intent(out) :: message
    integer :: ios

    status = status_ok
    message = ''
    location = card_error()
    e = 0.0_wp
    n = 0
    ! FORMAT 15 of the listing, with the blank mode made explicit.
    read (card, '(' // blank // ',E15.9,I2)', iostat=ios) e, n
    if (ios /= 0) then
      read (card(1:15), '(' // blank // ',E15.9)', iostat=ios) e
      if (ios /= 0) then
        call field_error(1, 15, status_card_not_numeric, &
            'expected a number (E, E15.9)')
        return
      end if
      read (card(16:17), '(' // blank // ',I2)', iostat=ios) n
      if (ios /= 0) then
        call field_error(16, 17, status_card_not_numeric, &
            'expected an integer (N, I2)')
        return
      end if
      call field_error(1, 17, status_card_not_numeric, &
          'expected E and N (FORMAT 15: E15.9,I2)')
      return
    end if
    if (.not. ieee_is_finite(e)) then
      call field_error(1, 15, status_card_not_finite, &
          'expected a finite number (E, E15.9) (NaN, Infinity or beyond' &
          // ' the range of this precision)')
      return
    end if
    if (len(requirement('E', e)) > 0) then
      call field_error(1, 15, status_out_of_range, 'expected ' &
          // requirement('E', e) // ' (E, E15.9)')
      return
    end if
    if (n < 1) then
      call field_error(16, 17, status_no_modes, &
          'expected N >= 1 (I2), the number of modes')
    end if

  contains

    subroutine field_error(c1, c2, code, expectation)
      integer, intent(in) :: c1, c2, code
      character(len=*), intent(in) :: expectation

      location = card_error(line, c1, c2)
      status = code
      message = 'card ' // integer_text(line) // ', columns ' &
          // integer_text(c1) // '-' // integer_text(c2) // ': found ' &
          // quoted(card(c1:c2)) // ', ' // expectation
    end subroutine field_error

  end subroutine read_card5

  !> A field's text for a message: quoted without its blanks, or 'a blank
  !> field'.
  pure function quoted(field) result(text)
    character(len=*), intent(in) :: field
    character(len=:), allocatable :: text

    if (len_trim(field) == 0) then
      text = 'a blank field'
    else
      text = '''' // trim(adjustl(field)) // ''''
    end if
  end function quoted

end module contactsep_cards
