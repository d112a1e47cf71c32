!> Working precision of the double build (the legacy -fdefault-real-8).
!> The restored core is one source compiled once per kind; each build
!> supplies its own module contactsep_kinds (see meson.build).
module contactsep_kinds
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  private
  public :: wp

  !> Kind of every REAL in the restored core.
  integer, parameter :: wp = real64
end module contactsep_kinds
