!> The extremes search's working arrays (model_extremes): the workspace
!> kept between blocks and batches, its growth, and the candidate list
!> (points within the tie of a design's best, from which the earliest is
!> taken).
module model_extremes_workspace
  use, intrinsic :: iso_fortran_env, only: int64
  use contactsep_kinds, only: wp
  implicit none
  private
  public :: reserve_slots, reserve_cells, offer, earliest

  !> Two values closer than tie * S are a tie: the earlier is reported.
  real(wp), parameter, public :: tie = 1.0e-12_wp
  !> A cell is finished when its bound is within converged * S of a value
  !> it holds.
  real(wp), parameter, public :: converged = 0.25e-12_wp

  !> Working arrays kept between blocks and batches (grown as needed).
  type, public :: extremes_workspace
    !> Per design slot and mode: p_j, c_j, |c_j|, cos and sin of p_j tau/2,
    !> floor(p_j tau/pi) (an integer, exact in a double: p_j tau < 2^52),
    !> and cos and sin of p_j r of the current level.
    real(wp), allocatable :: p(:, :), c(:, :), absc(:, :), cos0(:, :)
    real(wp), allocatable :: sin0(:, :), chain_c(:, :), chain_s(:, :)
    real(wp), allocatable :: quadrant(:, :)
    !> The level's per-slot-and-mode arc cosine and sine (-1, 0 for a whole
    !> turn) and Taylor weight (1 for a low mode, else 0).
    real(wp), allocatable :: arc_c(:, :), arc_s(:, :), low(:, :)
    !> Per slot: modes, cells (first, count), window, S, p_max,
    !> floor(p_min tau/pi), y3 and its slope at 0 and tau, best of y3 and
    !> -y3; the level's half-width, sum of |c_j| over whole turns, 1 where
    !> every mode is low, floors (best - tie - margin) and convergence
    !> slack; work done.
    integer, allocatable :: n(:), cells_of(:), first(:)
    real(wp), allocatable :: tau(:), scale(:), p_max(:), ends(:, :)
    real(wp), allocatable :: best(:, :), half_width(:), whole(:)
    real(wp), allocatable :: all_low(:), floor_value(:, :), conv(:)
    real(wp), allocatable :: min_quadrant(:)
    integer(int64), allocatable :: work(:)
    logical, allocatable :: gave_up(:), deferred(:), has_cells(:)
    logical :: overflow = .false.
    !> The cells: slot, centre, a_j, b_j, alive for max and min; a slot's
    !> cells are first(slot) .. first(slot) + cells_of(slot) - 1.
    integer :: cells = 0
    integer, allocatable :: slot(:), next_slot(:), which(:)
    real(wp), allocatable :: a(:, :), b(:, :), next_a(:, :), next_b(:, :)
    real(wp), allocatable :: centre(:), next_centre(:)
    logical, allocatable :: alive(:, :), next_alive(:, :), keep(:)
    !> Per cell: value, low-mode sums, bounds and certified values.
    real(wp), allocatable :: value(:), a_low(:), slope(:), curve_up(:)
    real(wp), allocatable :: curve_down(:), high_up(:)
    real(wp), allocatable :: high_down(:), bound(:, :), sure(:, :)
    real(wp), allocatable :: sure_at(:, :)
    !> Candidates: slot, side (1 max of y3, 2 max of -y3), time, value.
    integer :: candidates = 0
    integer, allocatable :: cand_slot(:), cand_side(:)
    real(wp), allocatable :: cand_t(:), cand_v(:)
  end type extremes_workspace

contains

  !> Room for `slots` designs of nm modes (the per-slot arrays).
  pure subroutine reserve_slots(ws, slots, nm)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots, nm

    if (allocated(ws%p)) then
      if (size(ws%p, 1) == slots .and. size(ws%p, 2) == nm) return
      deallocate(ws%p, ws%c, ws%absc, ws%cos0, ws%sin0, ws%chain_c, &
          ws%chain_s, ws%quadrant, ws%arc_c, ws%arc_s, ws%low, ws%n, &
          ws%cells_of, ws%first, ws%tau, ws%scale, ws%p_max, ws%ends, ws%best, &
          ws%half_width, ws%whole, ws%all_low, ws%floor_value, ws%conv, &
          ws%min_quadrant, ws%work, ws%gave_up, &
          ws%deferred, ws%has_cells)
    end if
    allocate(ws%p(slots, nm), ws%c(slots, nm), ws%absc(slots, nm), &
        ws%cos0(slots, nm), ws%sin0(slots, nm), ws%chain_c(slots, nm), &
        ws%chain_s(slots, nm), ws%quadrant(slots, nm), &
        ws%arc_c(slots, nm), ws%arc_s(slots, nm), ws%low(slots, nm), &
        ws%n(slots), ws%cells_of(slots), ws%first(slots), ws%tau(slots), &
        ws%scale(slots), &
        ws%p_max(slots), ws%ends(4, slots), ws%best(2, slots), &
        ws%half_width(slots), ws%whole(slots), ws%all_low(slots), &
        ws%floor_value(2, slots), ws%conv(slots), ws%min_quadrant(slots), &
        ws%work(slots), &
        ws%gave_up(slots), ws%deferred(slots), ws%has_cells(slots))
  end subroutine reserve_slots

  !> Room for `cells` cells of nm modes, keeping the current cells.
  pure subroutine reserve_cells(ws, cells, nm)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: cells, nm
    real(wp), allocatable :: a(:, :), b(:, :), centre(:)
    logical, allocatable :: alive(:, :), keep(:)
    integer, allocatable :: slot(:)
    integer :: room, old

    old = 0
    if (allocated(ws%a)) then
      if (size(ws%a, 1) >= cells .and. size(ws%a, 2) == nm) return
      if (size(ws%a, 2) == nm) old = size(ws%a, 1)
    end if
    room = max(cells, 2 * old, 256)
    allocate(a(room, nm), b(room, nm), centre(room), alive(room, 2), &
        keep(room), slot(room))
    if (old > 0) then
      a(1:old, :) = ws%a
      b(1:old, :) = ws%b
      centre(1:old) = ws%centre
      alive(1:old, :) = ws%alive
      keep(1:old) = ws%keep
      slot(1:old) = ws%slot
    end if
    call move_alloc(a, ws%a)
    call move_alloc(b, ws%b)
    call move_alloc(centre, ws%centre)
    call move_alloc(alive, ws%alive)
    call move_alloc(keep, ws%keep)
    call move_alloc(slot, ws%slot)
    if (allocated(ws%next_a)) deallocate(ws%next_a, ws%next_b, &
        ws%next_centre, ws%next_alive, ws%next_slot, ws%which, ws%value, &
        ws%a_low, ws%slope, ws%curve_up, ws%curve_down, ws%high_up, &
        ws%high_down, ws%bound, ws%sure, ws%sure_at)
    allocate(ws%next_a(room, nm), ws%next_b(room, nm), &
        ws%next_centre(room), ws%next_alive(room, 2), ws%next_slot(room), &
        ws%which(room), ws%value(room), ws%a_low(room), ws%slope(room), &
        ws%curve_up(room), ws%curve_down(room), &
        ws%high_up(room), ws%high_down(room), ws%bound(room, 2), &
        ws%sure(room, 2), ws%sure_at(room, 2))
  end subroutine reserve_cells

  !> A point as a candidate of a design (slot) for side 1 (max of y3) or 2
  !> (max of -y3): the best value rises; points within the tie are kept.
  pure subroutine offer(ws, slot, side, t, value)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slot, side
    real(wp), intent(in) :: t, value
    integer, allocatable :: grown_int(:)
    real(wp), allocatable :: grown(:)
    integer :: room

    ws%best(side, slot) = max(ws%best(side, slot), value)
    if (value < ws%best(side, slot) - tie * ws%scale(slot)) return
    if (.not. allocated(ws%cand_t)) then
      allocate(ws%cand_slot(256), ws%cand_side(256), ws%cand_t(256), &
          ws%cand_v(256))
    else if (ws%candidates == size(ws%cand_t)) then
      room = 2 * size(ws%cand_t)
      allocate(grown_int(room))
      grown_int(1:room / 2) = ws%cand_slot
      call move_alloc(grown_int, ws%cand_slot)
      allocate(grown_int(room))
      grown_int(1:room / 2) = ws%cand_side
      call move_alloc(grown_int, ws%cand_side)
      allocate(grown(room))
      grown(1:room / 2) = ws%cand_t
      call move_alloc(grown, ws%cand_t)
      allocate(grown(room))
      grown(1:room / 2) = ws%cand_v
      call move_alloc(grown, ws%cand_v)
    end if
    ws%candidates = ws%candidates + 1
    ws%cand_slot(ws%candidates) = slot
    ws%cand_side(ws%candidates) = side
    ws%cand_t(ws%candidates) = t
    ws%cand_v(ws%candidates) = value
  end subroutine offer

  !> Earliest and latest time of each design's points within the tie of
  !> its best (side 1: y3, 2: -y3), in one pass over the candidates.
  pure subroutine earliest(ws, slots, first, last)
    type(extremes_workspace), intent(in) :: ws
    integer, intent(in) :: slots
    real(wp), intent(out) :: first(2, slots), last(2, slots)
    integer :: i, s, side

    first = huge(1.0_wp)
    last = -huge(1.0_wp)
    do i = 1, ws%candidates
      s = ws%cand_slot(i)
      side = ws%cand_side(i)
      if (ws%cand_v(i) >= ws%best(side, s) - tie * ws%scale(s)) then
        first(side, s) = min(first(side, s), ws%cand_t(i))
        last(side, s) = max(last(side, s), ws%cand_t(i))
      end if
    end do
  end subroutine earliest

end module model_extremes_workspace
