!> The listing text: each WRITE(6,10) of Appendix G as one line.
!>
!> Records are formatted by gfortran itself with FORMAT 10 (7F15.9)
!> through an internal WRITE, so overflow stars, '-0.000000000' and the
!> last digit come out as the original program prints them.  A record of
!> k values is 15*k characters, then LF, as gfortran writes it to stdout.
module contactsep_listing
  use contactsep_kinds, only: wp
  use contactsep_status, only: message_length, status_ok, &
      status_listing_full, status_out_of_memory, status_format_failed, &
      integer_text
  implicit none
  private
  public :: listing_text, start_listing, reserve_listing, write_record

  !> Width of one F15.9 field.
  integer, parameter :: field_width = 15
  !> Values per FORMAT 10 record (a longer list would wrap).
  integer, parameter :: record_values = 7
  !> Bytes the text starts with; it doubles up to the capacity.
  integer, parameter :: initial_bytes = 4096

  !> Listing text of one data set, at most capacity bytes.
  type :: listing_text
    character(len=:), allocatable :: text
    !> Bytes written so far: text(1:length).
    integer :: length = 0
    integer :: capacity = 0
    !> False: records are counted as written but neither formatted nor
    !> kept (a caller that never reads the text).
    logical :: enabled = .true.
  end type listing_text

contains

  !> An empty listing that may grow to capacity bytes.
  pure subroutine start_listing(listing, capacity, enabled)
    type(listing_text), intent(out) :: listing
    integer, intent(in) :: capacity
    !> Whether to keep the text (default true).
    logical, intent(in), optional :: enabled

    listing%capacity = max(capacity, 0)
    listing%length = 0
    listing%text = ''
    listing%enabled = .true.
    if (present(enabled)) listing%enabled = enabled
  end subroutine start_listing

  !> Make room for bytes more bytes (at most the capacity) at once.
  !>
  !> A caller that knows what is left to list calls this so that the
  !> text is allocated once at its size, not grown by doubling (which
  !> holds the old and the new text at once: 1.5x the listing at the
  !> end).  Pages never written are never touched, so reserving a few
  !> lines too many costs nothing.  A failed allocation is not an error
  !> here: write_record then grows the text as before.
  subroutine reserve_listing(listing, bytes)
    type(listing_text), intent(inout) :: listing
    !> Bytes still to be written.
    integer, intent(in) :: bytes
    character(len=:), allocatable :: grown
    integer :: new_size, stat

    if (.not. listing%enabled .or. bytes <= 0) return
    new_size = listing%length + min(bytes, listing%capacity &
        - listing%length)
    if (new_size <= len(listing%text)) return
    allocate (character(len=new_size) :: grown, stat=stat)
    if (stat /= 0) return
    grown(1:listing%length) = listing%text(1:listing%length)
    call move_alloc(grown, listing%text)
  end subroutine reserve_listing

  !> Append one record of at most 7 values, formatted with (7F15.9).
  !>
  !> A record that does not fit is not written at all, so the text always
  !> ends with a whole line.
  subroutine write_record(listing, values, status, message)
    type(listing_text), intent(inout) :: listing
    real(wp), intent(in) :: values(:)
    integer, intent(out) :: status
    character(len=message_length), intent(out) :: message
    character(len=record_values * field_width) :: record
    character(len=message_length) :: io_message
    character(len=:), allocatable :: grown
    integer :: width, ios, new_size, stat

    status = status_ok
    message = ''
    if (size(values) > record_values) then
      status = status_format_failed
      message = 'a listing record holds at most 7 values, not ' &
          // integer_text(size(values))
      return
    end if
    width = size(values) * field_width
    if (.not. listing%enabled) return
    write (record, '(7F15.9)', iostat=ios, iomsg=io_message) values
    if (ios /= 0) then
      status = status_format_failed
      message = 'a listing record could not be formatted: ' &
          // trim(io_message)
      return
    end if
    ! Compared this way round so that no sum can overflow.
    if (width + 1 > listing%capacity - listing%length) then
      status = status_listing_full
      message = 'the listing needs more than ' &
          // integer_text(listing%capacity) // ' bytes (max_listing)'
      return
    end if
    if (width + 1 > len(listing%text) - listing%length) then
      if (len(listing%text) > listing%capacity / 2) then
        new_size = listing%capacity
      else
        new_size = min(listing%capacity, max(initial_bytes, &
            2 * len(listing%text), listing%length + width + 1))
      end if
      allocate (character(len=new_size) :: grown, stat=stat)
      if (stat /= 0) then
        status = status_out_of_memory
        message = 'no memory for a listing of ' // integer_text(new_size) &
            // ' bytes'
        return
      end if
      grown(1:listing%length) = listing%text(1:listing%length)
      call move_alloc(grown, listing%text)
    end if
    listing%text(listing%length + 1:listing%length + width) = record(1:width)
    listing%length = listing%length + width + 1
    listing%text(listing%length:listing%length) = achar(10)
  end subroutine write_record

end module contactsep_listing
