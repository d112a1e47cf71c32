!> The state of one run of the adaptive stepper (chatter_adaptive): the
!> system, the flow's tables, the current state and what is known of it,
!> the steps waiting for the search of the largest gap, and the outputs
!> the searches fill.  The stepper's procedures (chatter_adaptive_flow,
!> chatter_adaptive_gap_max, chatter_adaptive_crossings and the driver,
!> chatter_adaptive) share it through a `type(adaptive_run)` argument.
module chatter_adaptive_state
  use contactsep_kinds, only: wp
  use chatter_status, only: status_ok
  use chatter_contact_law, only: contact_law, max_contacts
  implicit none
  private
  public :: adaptive_run
  public :: max_level, max_stack, max_tol, max_waiting, head

  !> Flight steps of up to 2^max_level dt.
  integer, parameter :: max_level = 30
  !> Intervals held by a search (depth-first, one split adds one).
  integer, parameter :: max_stack = 400
  !> Relative tolerance of the largest gap.
  real(wp), parameter :: max_tol = 1.0e-6_wp
  !> Steps whose search for the largest gap waits for the end of the run
  !> (by then the running largest gap excludes most of them).
  integer, parameter :: max_waiting = 64
  !> Header of a waiting step: its end time, length, upper bound, gaps
  !> and rates at its ends, moving modes, the still modes' part of gap.
  integer, parameter :: head = 9

  !> One run: modes 1..n (all members stacked), contacts 1..k (1 or 2).
  !> Lengths in in, times in s, forces in lb (the driver's arguments).
  !> The driver's start() allocates the arrays; after it, whole-array
  !> assignments write x(:) = ..., which skips the reallocation check
  !> on the hot path.
  type :: adaptive_run
    !> Modes and contacts.
    integer :: n = 0, k = 0
    !> Mass and frequency (rad/s) of every mode.
    real(wp), allocatable :: m(:), p(:)
    !> ht(:, c): contact c's Jacobian h(c, :); the gap offsets g0.
    real(wp), allocatable :: ht(:, :), g0(:)
    !> Hertz constant (lb/in^1.5), damping chi (s/in), Newton's
    !> coefficient of restitution, step dt (s), open threshold (in).
    real(wp) :: stiffness = 0.0_wp, chi = 0.0_wp, restitution = 0.0_wp
    !> The Hertz family's force law and its memory (chatter_contact_law;
    !> the driver sets it from stiffness and chi, or takes it whole),
    !> and the damping's work so far (in lb).
    type(contact_law) :: law
    real(wp) :: damped_work = 0.0_wp
    real(wp) :: dt = 0.0_wp, threshold = 0.0_wp
    !> The energy's hard bound (in lb): a fixed step past it stops the
    !> run (status_energy_bound), as every bound above assumes it.
    real(wp) :: energy_bound = huge(1.0_wp)
    !> The static correction's series flexibilities (in/lb) and whether
    !> any is nonzero (else the plain truncation's forces, bit for bit);
    !> while frozen, shift(c) = (C lambda)_c of the still contacts'
    !> forces, which the physical gap of a considered contact adds to
    !> its modal gap (0 once thawed, or without the correction).
    real(wp), allocatable :: cmat(:, :), shift(:)
    logical :: series = .false.
    !> Rotation by the exact flow: cos(p tau), sin(p tau) / p and
    !> p sin(p tau) for tau in slot -2 (the sample stride), -1 (dt/2),
    !> 0 (the whole run),
    !> 1..levels (2^(slot-1) dt).
    real(wp), allocatable :: tab_c(:, :), tab_s(:, :), tab_p(:, :)
    integer :: levels = 0
    !> Half a step's kick of a unit force at contact c: dt/2 h_c / m;
    !> an impulse's: h_c / m.
    real(wp), allocatable :: half_kick(:, :), inv_mh(:, :)
    !> Contact c's Jacobian is 0 outside modes lo(c)..hi(c) (each
    !> contact touches two of the three members): its kicks and rates
    !> skip the rest.
    integer :: lo(max_contacts) = 1, hi(max_contacts) = 0
    !> D = H M^-1 H^T: an impulse P changes the contact rates by D P.
    real(wp), allocatable :: coupling(:, :)
    !> A bound of |g_c''| from the energy bound of the run (free).
    real(wp), allocatable :: energy_b(:)
    !> Modal displacements and velocities.
    real(wp), allocatable :: q(:), v(:)
    !> Modes 1..moving move; the rest are held still (frozen) until the
    !> first fixed step, their part of the gaps in g_still.
    integer :: moving = 0
    logical :: frozen = .false.
    real(wp), allocatable :: g_still(:)
    !> The column of ht that flow() sums as the second gap (2, or 1 with
    !> one contact).
    integer :: h2 = 1
    !> Gaps and their rates now and after the last flow; B_c (see the
    !> driver's module comment); the contact forces of a Hertz step.
    real(wp), allocatable :: gap(:), gap_new(:), rate(:), rate_new(:)
    real(wp), allocatable :: bound(:), force(:)
    !> The fixed step whose start the forces in force (and the undamped
    !> ones in elastic) are of: a Hertz step's end forces are the next
    !> step's start forces where no force depends on v (chi = 0; the
    !> undamped ones never do), so it reuses them (-1: none held).
    integer :: forces_at = -1, elastic_at = -1
    real(wp) :: elastic(max_contacts) = 0.0_wp
    !> The amplitudes of the segment being searched (valid if amp_now).
    real(wp), allocatable :: amp(:)
    logical :: amp_now = .false.
    !> bound, rate and e_modal hold for the current state.
    logical :: amp_fresh = .false., rate_fresh = .false.
    logical :: e_fresh = .false.
    !> Modal energy (in lb) of the current state when e_fresh.
    real(wp) :: e_modal = 0.0_wp
    !> Time (s) at the end of the step being taken.
    real(wp) :: t_now = 0.0_wp
    !> The waiting steps (header, then q and v at the step's end).
    real(wp), allocatable :: waiting(:, :)
    integer :: n_waiting = 0
    !> Contact 1's first episode: 0 before it, 1 in it, 2 after it;
    !> first = its start (s) and impulse (lb s), as the driver returns.
    integer :: episode = 0
    real(wp) :: first(2) = -1.0_wp
    !> crossings(:, i) = time, +c (contact c opens) or -c (it closes),
    !> n_cross of the table's max_cross filled: the driver's output
    !> table (associated during its call only).
    real(wp), pointer, contiguous :: crossings(:, :) => null()
    integer :: n_cross = 0, max_cross = 0
    !> gap_max(:, c) = largest gap c so far and its time.
    real(wp), allocatable :: gap_max(:, :)
    !> Flight steps, fixed steps, flow evaluations of the searches.
    integer :: counts(3) = 0
    !> The stop at the first discontinuity event (chatter_adaptive_event):
    !> the circuit's opening that stops the run (s; < 0: never stop),
    !> the crossings read so far, each contact's state by them, and the
    !> instant the circuit opened (< 0: it is closed).
    real(wp) :: stop_open = -1.0_wp, circuit_from = -1.0_wp
    integer :: n_read = 0
    logical :: is_open(max_contacts) = .false.
    !> A chatter_status code.
    integer :: status = status_ok
  end type adaptive_run

end module chatter_adaptive_state
