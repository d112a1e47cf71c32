!> The range each value of a data set must lie in.
!>
!> The original program takes any number: a zero modulus or time step
!> makes it loop for ever, a zero length or k_jL divides by zero, a
!> negative size or density takes a square root of a negative number.
!> The card reader checks every field it reads against these ranges, and
!> solve checks the values it is given, so a deck and a designer's direct
!> call are refused alike, naming the value and what it must be.
module contactsep_validation
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use contactsep_kinds, only: wp
  use contactsep_lower_contact, only: tau
  implicit none
  private
  public :: requirement

  !> Values on cards 1-6 (N excluded), in card order.
  integer, parameter, public :: scalar_count = 18
  !> Columns of the modes table: V,C,ALPHA, V2,C2,ALPH2, V3,C3,ALPH3.
  integer, parameter, public :: mode_column_count = 9
  !> Most lines of the lower-contact history up to TAU: with more, a
  !> listing would run to tens of megabytes (DELT >= TAU / 1e6 = 6e-8 s).
  integer, parameter, public :: max_history_lines = 1000000

  !> Listing names of the values of cards 1-6, in card order.
  character(len=5), parameter, public :: scalar_names(scalar_count) = [ &
      'XL   ', 'B    ', 'H    ', 'RHO  ', 'YSTAT', &
      'XL2  ', 'B2   ', 'H2   ', 'RHO2 ', &
      'XL3  ', 'B3   ', 'H3   ', 'RHO3 ', &
      'DELT ', 'ER   ', 'DELY ', &
      'E    ', 'XL2C ']
  !> Listing names of the three values on each mode card.
  character(len=5), parameter, public :: mode_names(mode_column_count) = [ &
      'V    ', 'C    ', 'ALPHA', 'V2   ', 'C2   ', 'ALPH2', &
      'V3   ', 'C3   ', 'ALPH3']

contains

  !> What the value named `name` (a listing name) must be, or '' when
  !> `value` already is.  YSTAT, DELY and the mode values C, ALPHA may be
  !> any finite number (whether the release point is above the separator
  !> is the solver's question).
  function requirement(name, value) result(expected)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: value
    character(len=:), allocatable :: expected

    expected = ''
    if (.not. ieee_is_finite(value)) then
      expected = 'a finite number'
      return
    end if
    select case (trim(name))
    case ('XL', 'XL2', 'XL3', 'XL2C')
      if (.not. value > 0.0_wp) expected = 'a positive length, in'
    case ('B', 'B2', 'B3')
      if (.not. value > 0.0_wp) expected = 'a positive width, in'
    case ('H', 'H2', 'H3')
      if (.not. value > 0.0_wp) expected = 'a positive thickness, in'
    case ('RHO', 'RHO2', 'RHO3')
      if (.not. value > 0.0_wp) expected = &
          'a positive weight density, lb/ft^3'
    case ('E')
      if (.not. value > 0.0_wp) expected = 'a positive modulus, psi'
    case ('ER')
      if (value < 0.0_wp .or. value > 1.0_wp) expected = &
          'a coefficient of restitution in [0, 1]'
    case ('DELT')
      if (.not. value > 0.0_wp) then
        expected = 'a positive time step, s'
      else if (tau / value > real(max_history_lines, wp)) then
        expected = 'a time step of at least 6.0E-8 s (the history to' &
            // ' TAU = 0.060 s has at most 1000000 lines)'
      end if
    case ('V', 'V2', 'V3')
      if (.not. value > 0.0_wp) expected = 'a positive eigenvalue k_jL'
    end select
  end function requirement

end module contactsep_validation
