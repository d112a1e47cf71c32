!> Extremes of the lower-contact response y3(t) = sum_j c_j sin(p_j t) over
!> 0 <= t <= tau, true to 1e-12 of S = sum |c_j| (docs/model.md, "The
!> extremes of y3"; python/contactsep/model/twin_extremes.py is the NumPy twin).
!>
!> Branch and bound over a list of cells, for a block of designs at once.
!> Every design's window is halved level by level; a live cell carries
!> a_j = c_j sin(p_j m) and b_j = c_j cos(p_j m) at its centre m, rotated
!> from its parent's by the level's exact half-angle.  The bounds of a cell
!> (model_extremes_bounds; model_extremes_cells runs a level) decide
!> whether it is dropped (it cannot come within the tie of the best value
!> found), finished (its bound is within `converged` of a value it holds)
!> or halved.  The search ends when no cell is left, or gives up
!> (resolved = .false.) when a design's work budget runs out: it never
!> returns an unrefined value.
!>
!> Phases are exact: p_j tau/2 = hi + lo (Dekker), sin and cos of the root
!> centre from sin(hi) and cos(hi) corrected by lo, every finer level's
!> half-angle from the coarser one by the half-angle formulas, its quadrant
!> read from the bits of floor(p_j tau/pi) (a three-double pi).
!>
!> Memory: a design with more than `block_cell_budget` live cell-modes in
!> a block is searched again on its own, its window in time-ordered
!> segments (one needing more than `cell_budget` halved again).
module model_extremes
  use, intrinsic :: iso_fortran_env, only: int64
  use contactsep_kinds, only: wp
  use model_extremes_workspace, only: extremes_workspace, tie, &
      reserve_slots, reserve_cells, offer, earliest
  use model_extremes_cells, only: search_level, halve, quarter
  implicit none
  private
  public :: extremes, extremes_workspace

  !> Most cell-mode evaluations per design before the search gives up.
  integer(int64), parameter, public :: work_budget = 2_int64**31
  !> Most live cell-modes of a design in a block, and of a segment.
  integer(int64), parameter, public :: block_cell_budget = 2_int64**14
  integer(int64), parameter, public :: cell_budget = 2_int64**18
  !> Most designs searched together; a block holds about block_modes of
  !> their modes, and at least 8 designs (its cells' arrays then stay in
  !> cache: 16 designs of 32 modes were 2-3 % faster than 32 designs, the
  !> benchmark's designs of 4 modes within 1 % from 32 to 128).
  integer, parameter, public :: block_size = 64
  integer, parameter :: block_modes = 512
  !> Deepest level (cells tau/2^61 wide).
  integer, parameter :: max_depth = 60
  !> Deepest segment of a design searched alone (tau/2^24 wide).
  integer, parameter :: max_segment_levels = 24
  real(wp), parameter :: split = 134217729.0_wp
  real(wp), parameter :: pi_parts(3) = [3.141592653589793116_wp, &
      1.2246467991473532e-16_wp, -2.9947698097183397e-33_wp]
  real(wp), parameter :: pi = pi_parts(1)

contains

  !> Largest and smallest y3 over [0, tau(i)] of designs i = 1..m and their
  !> times (the earliest within the tie), whether the largest sits at tau,
  !> whether a point more than half a shortest period away ties with
  !> either, and whether the search finished within its budget (else the
  !> values are not set).  Designs with search(i) false are skipped.
  pure subroutine extremes(c, p, n, tau, search, ws, y_max, t_max, y_min, &
      t_min, at_end, max_tied, min_tied, resolved)
    !> Coefficients c_j (in) and frequencies p_j > 0 (rad/s) of design i in
    !> column i, its first n(i) entries.
    real(wp), intent(in) :: c(:, :), p(:, :)
    integer, intent(in) :: n(:)
    !> Window lengths (s), > 0.
    real(wp), intent(in) :: tau(:)
    logical, intent(in) :: search(:)
    type(extremes_workspace), intent(inout) :: ws
    real(wp), intent(out) :: y_max(:), t_max(:), y_min(:), t_min(:)
    logical, intent(out) :: at_end(:), max_tied(:), min_tied(:)
    logical, intent(out) :: resolved(:)
    integer :: designs(block_size), first, i, count, slot, room
    real(wp) :: first_t(2, block_size), last_t(2, block_size)

    y_max = 0.0_wp; t_max = 0.0_wp; y_min = 0.0_wp; t_min = 0.0_wp
    at_end = .false.; max_tied = .false.; min_tied = .false.
    resolved = .false.
    room = min(block_size, max(8, block_modes / max(1, maxval(n, &
        mask=search, dim=1))))
    first = 1
    do while (first <= size(tau))
      count = 0
      i = first
      do while (i <= size(tau) .and. count < room)
        if (search(i)) then
          count = count + 1
          designs(count) = i
        end if
        i = i + 1
      end do
      first = i
      if (count == 0) cycle
      call start_block(c, p, n, tau, designs(1:count), ws)
      call search_block(ws, count)
      do slot = 1, count
        if (ws%deferred(slot)) call search_alone(ws, slot)
      end do
      call earliest(ws, count, first_t(:, 1:count), last_t(:, 1:count))
      do slot = 1, count
        i = designs(slot)
        resolved(i) = .not. ws%gave_up(slot)
        y_max(i) = ws%best(1, slot)
        y_min(i) = -ws%best(2, slot)
        t_max(i) = first_t(1, slot)
        t_min(i) = first_t(2, slot)
        at_end(i) = t_max(i) == ws%tau(slot)
        max_tied(i) = last_t(1, slot) - t_max(i) > pi / ws%p_max(slot)
        min_tied(i) = last_t(2, slot) - t_min(i) > pi / ws%p_max(slot)
      end do
    end do
  end subroutine extremes

  !> Per-design set-up of a block: modes, exact root phases, quadrants,
  !> y3 and its slope at both ends, the ends as candidates, and one cell
  !> (the whole window) per design with a search to do.
  pure subroutine start_block(c, p, n, tau, designs, ws)
    real(wp), intent(in) :: c(:, :), p(:, :), tau(:)
    integer, intent(in) :: n(:), designs(:)
    type(extremes_workspace), intent(inout) :: ws
    integer :: slot, i, j, nm, side, cells
    real(wp) :: sgn

    nm = maxval(n(designs))
    call reserve_slots(ws, size(designs), nm)
    ws%candidates = 0
    cells = 0
    do slot = 1, size(designs)
      i = designs(slot)
      ws%n(slot) = n(i)
      ws%tau(slot) = tau(i)
      ws%p(slot, :) = 0.0_wp
      ws%absc(slot, :) = 0.0_wp
      ws%c(slot, :) = 0.0_wp
      ws%p(slot, 1:n(i)) = p(1:n(i), i)
      ws%c(slot, 1:n(i)) = c(1:n(i), i)
      ws%absc(slot, 1:n(i)) = abs(c(1:n(i), i))
      ws%scale(slot) = sum(ws%absc(slot, 1:n(i)))
      ws%p_max(slot) = maxval(p(1:n(i), i))
      ws%work(slot) = 0
      ws%best(:, slot) = -huge(1.0_wp)
      ws%deferred(slot) = .false.
      ws%gave_up(slot) = .not. (ws%p_max(slot) * tau(i) < 2.0_wp**52)
      do j = 1, nm
        call root_phase(ws%p(slot, j), tau(i), ws%cos0(slot, j), &
            ws%sin0(slot, j), ws%quadrant(slot, j))
      end do
      ws%min_quadrant(slot) = minval(ws%quadrant(slot, 1:n(i)))
      ws%ends(:, slot) = [0.0_wp, sum(ws%c(slot, :) * ws%p(slot, :)), &
          sum(ws%c(slot, :) * 2.0_wp * ws%sin0(slot, :) * ws%cos0(slot, :)), &
          sum(ws%c(slot, :) * ws%p(slot, :) * (ws%cos0(slot, :)**2 &
          - ws%sin0(slot, :)**2))]
      do side = 1, 2
        sgn = merge(1.0_wp, -1.0_wp, side == 1)
        call offer(ws, slot, side, 0.0_wp, 0.0_wp)
        call offer(ws, slot, side, tau(i), sgn * ws%ends(3, slot))
      end do
      ws%first(slot) = cells + 1
      ws%cells_of(slot) = 0
      if (ws%gave_up(slot) .or. .not. ws%scale(slot) > 0.0_wp) cycle
      cells = cells + 1
      ws%cells_of(slot) = 1
      call reserve_cells(ws, cells, nm)
      ws%slot(cells) = slot
      ws%centre(cells) = 0.5_wp * tau(i)
      ws%a(cells, :) = ws%c(slot, :) * ws%sin0(slot, :)
      ws%b(cells, :) = ws%c(slot, :) * ws%cos0(slot, :)
      ws%alive(cells, :) = .true.
      ws%chain_c(slot, :) = ws%cos0(slot, :)
      ws%chain_s(slot, :) = ws%sin0(slot, :)
    end do
    ws%cells = cells
  end subroutine start_block

  !> cos and sin of p tau/2 from the exact product, and floor(p tau/pi):
  !> its bits l and l+1 are the quadrant of p tau/2^(l+1).
  elemental subroutine root_phase(p, tau, cos0, sin0, quadrant)
    real(wp), intent(in) :: p, tau
    real(wp), intent(out) :: cos0, sin0
    real(wp), intent(out) :: quadrant
    real(wp) :: hi, lo, k, rest, u, e, ch, sh
    integer :: part

    call two_product(p, 0.5_wp * tau, hi, lo)
    ch = cos(hi)
    sh = sin(hi)
    cos0 = ch - lo * sh
    sin0 = sh + lo * ch
    call two_product(p, tau, hi, lo)
    k = aint(hi / pi)
    rest = hi
    do part = 1, 3
      call two_product(k, pi_parts(part), u, e)
      rest = (rest - u) - e
    end do
    rest = rest + lo
    quadrant = k + real(floor(rest / pi, int64), wp)
  end subroutine root_phase

  !> (hi, lo) with hi + lo = x y exactly (Dekker; no fused multiply-add).
  elemental subroutine two_product(x, y, hi, lo)
    real(wp), intent(in) :: x, y
    real(wp), intent(out) :: hi, lo
    real(wp) :: t, xh, xl, yh, yl

    hi = x * y
    t = split * x
    xh = t - (t - x)
    xl = x - xh
    t = split * y
    yh = t - (t - y)
    yl = y - yh
    lo = ((xh * yh - hi) + xh * yl + xl * yh) + xl * yl
  end subroutine two_product

  !> Levels until no cell is left; a design over the block's cell budget
  !> is deferred (searched again alone), one over its work budget or the
  !> deepest level gives up.
  pure subroutine search_block(ws, slots)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots
    integer :: level

    do level = 0, max_depth
      call count_cells(ws, slots, block_cell_budget, .true.)
      if (ws%cells == 0) return
      call search_level(ws, slots, level)
    end do
    call count_cells(ws, slots, block_cell_budget, .true.)
    ws%gave_up(1:slots) = ws%gave_up(1:slots) .or. ws%has_cells(1:slots)
  end subroutine search_block

  !> Add each design's live cells to its work; drop the cells of designs
  !> over a budget (deferred when `defer`, else overflowing).
  pure subroutine count_cells(ws, slots, budget, defer)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots
    integer(int64), intent(in) :: budget
    logical, intent(in) :: defer
    integer :: slot, kept, lo, count
    logical :: drop(slots)

    do slot = 1, slots
      ws%has_cells(slot) = ws%cells_of(slot) > 0
      ws%work(slot) = ws%work(slot) + int(ws%cells_of(slot), int64) &
          * ws%n(slot)
      if (ws%work(slot) > work_budget) ws%gave_up(slot) = .true.
      if (.not. ws%gave_up(slot) .and. int(ws%cells_of(slot), int64) &
          * ws%n(slot) > budget) then
        if (defer) then
          ws%deferred(slot) = .true.
        else
          ws%overflow = .true.
        end if
      end if
      drop(slot) = ws%gave_up(slot) .or. ws%deferred(slot)
    end do
    if (.not. defer .and. ws%overflow) drop = .true.
    if (.not. any(drop .and. ws%has_cells(1:slots))) return
    kept = 0
    do slot = 1, slots
      lo = ws%first(slot)
      count = ws%cells_of(slot)
      ws%first(slot) = kept + 1
      if (drop(slot)) then
        ws%cells_of(slot) = 0
        cycle
      end if
      if (lo /= kept + 1 .and. count > 0) then
        ws%slot(kept + 1:kept + count) = ws%slot(lo:lo + count - 1)
        ws%centre(kept + 1:kept + count) = ws%centre(lo:lo + count - 1)
        ws%a(kept + 1:kept + count, :) = ws%a(lo:lo + count - 1, :)
        ws%b(kept + 1:kept + count, :) = ws%b(lo:lo + count - 1, :)
        ws%alive(kept + 1:kept + count, :) = ws%alive(lo:lo + count - 1, :)
      end if
      kept = kept + count
    end do
    ws%cells = kept
  end subroutine count_cells

  !> A deferred design searched alone, a segment of its window at a time
  !> in time order: a segment that needs more than cell_budget live
  !> cell-modes is searched again as its two halves (a stack of pending
  !> segments: level and index, the left half on top).
  pure subroutine search_alone(ws, slot)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slot
    integer :: seg_level(max_segment_levels + 2)
    integer :: seg_index(max_segment_levels + 2)
    integer :: depth, top, index, level, nm
    real(wp), allocatable :: a(:), b(:), t(:), ch(:), sh(:), hc(:), hs(:)
    real(wp) :: centre, step, turn

    ! the slot becomes the first, alone in the block
    if (slot /= 1) call move_slot(ws, slot, 1)
    nm = size(ws%p, 2)
    allocate(a(nm), b(nm), t(nm), ch(nm), sh(nm), hc(nm), hs(nm))
    ws%deferred(1) = .false.
    depth = 1
    seg_level(1) = 0
    seg_index(1) = 0
    do while (depth > 0 .and. .not. ws%gave_up(1))
      top = seg_level(depth)
      index = seg_index(depth)
      depth = depth - 1
      ! walk from the root to the segment, left or right by its bits
      a = ws%c(1, :) * ws%sin0(1, :)
      b = ws%c(1, :) * ws%cos0(1, :)
      ch = ws%cos0(1, :)
      sh = ws%sin0(1, :)
      centre = 0.5_wp * ws%tau(1)
      do level = 1, top
        call halve(ch, sh, quarter(ws%quadrant(1, :), level), &
            hc, hs)
        ch = hc
        sh = hs
        turn = merge(1.0_wp, -1.0_wp, btest(index, top - level))
        step = ws%tau(1) * 0.5_wp**(level + 1)
        t = a * ch + turn * b * sh
        b = b * ch - turn * a * sh
        a = t
        centre = centre + turn * step
      end do
      call reserve_cells(ws, 1, nm)
      ws%cells = 1
      ws%first(1) = 1
      ws%cells_of(1) = 1
      ws%slot(1) = 1
      ws%centre(1) = centre
      ws%a(1, :) = a
      ws%b(1, :) = b
      ws%alive(1, :) = .true.
      ws%chain_c(1, :) = ch
      ws%chain_s(1, :) = sh
      ws%overflow = .false.
      do level = top, max_depth
        call count_cells(ws, 1, cell_budget, .false.)
        if (ws%cells == 0 .or. ws%gave_up(1) .or. ws%overflow) exit
        call search_level(ws, 1, level)
      end do
      if (ws%overflow) then
        if (top == max_segment_levels) then
          ws%gave_up(1) = .true.
        else
          seg_level(depth + 1:depth + 2) = top + 1
          seg_index(depth + 1) = 2 * index + 1
          seg_index(depth + 2) = 2 * index
          depth = depth + 2
        end if
      else if (ws%cells > 0) then
        ws%gave_up(1) = .true.
      end if
    end do
    if (slot /= 1) call move_slot(ws, 1, slot)
  end subroutine search_alone

  !> Swap two designs' slots (their modes, state and candidates).
  pure subroutine move_slot(ws, from, to)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: from, to
    integer :: k

    call swap_rows(ws%p, from, to)
    call swap_rows(ws%c, from, to)
    call swap_rows(ws%absc, from, to)
    call swap_rows(ws%cos0, from, to)
    call swap_rows(ws%sin0, from, to)
    ws%quadrant([from, to], :) = ws%quadrant([to, from], :)
    ws%n([from, to]) = ws%n([to, from])
    ws%tau([from, to]) = ws%tau([to, from])
    ws%scale([from, to]) = ws%scale([to, from])
    ws%p_max([from, to]) = ws%p_max([to, from])
    ws%min_quadrant([from, to]) = ws%min_quadrant([to, from])
    ws%ends(:, [from, to]) = ws%ends(:, [to, from])
    ws%best(:, [from, to]) = ws%best(:, [to, from])
    ws%work([from, to]) = ws%work([to, from])
    ws%gave_up([from, to]) = ws%gave_up([to, from])
    ws%deferred([from, to]) = ws%deferred([to, from])
    do k = 1, ws%candidates
      if (ws%cand_slot(k) == from) then
        ws%cand_slot(k) = to
      else if (ws%cand_slot(k) == to) then
        ws%cand_slot(k) = from
      end if
    end do
  end subroutine move_slot

  pure subroutine swap_rows(x, i, j)
    real(wp), intent(inout) :: x(:, :)
    integer, intent(in) :: i, j

    x([i, j], :) = x([j, i], :)
  end subroutine swap_rows

end module model_extremes
