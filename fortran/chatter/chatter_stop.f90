!> A stop asked for from outside a running stepper (issue 31): Python
!> runs a long stepper call in a thread with the GIL released and, when
!> Ctrl-C or SIGTERM arrives in its main thread, calls request_stop
!> (chatter_api); every stepper loop reads the flag every
!> stop_check_every steps and returns status_interrupted.  VOLATILE:
!> another thread writes it while a loop reads it, so the compiler must
!> not keep it in a register.
module chatter_stop
  implicit none
  private

  !> Nonzero: the running steppers should stop.
  integer, volatile, public :: stop_requested = 0
  !> Steps between two looks at the flag (a few microseconds each at
  !> N = 4; a few milliseconds at N = 1024).
  integer, parameter, public :: stop_check_every = 4096
end module chatter_stop
