!> Working precision of the single build: the listing's REAL.
!> The restored core is one source compiled once per kind; each build
!> supplies its own module contactsep_kinds (see meson.build).
module contactsep_kinds
  use, intrinsic :: iso_fortran_env, only: real32
  implicit none
  private
  public :: wp

  !> Kind of every REAL in the restored core.
  integer, parameter :: wp = real32
end module contactsep_kinds
