!> One level of the extremes search (model_extremes) on a block of designs:
!> the level's arcs from the exact half-angle chain (its quadrants read from
!> the bits of floor(p_j tau/pi)), every live cell bounded
!> (model_extremes_bounds), its centre and certified points offered as
!> candidates, then dropped, finished, polished (model_extremes_bounds;
!> cells with p_max r <= phi_polish) or halved.
!>
!> Cells are vectors (contiguous, a design's together, in time order); a
!> step runs a design's cells at a time where its scalars would otherwise
!> be gathered per cell, else over all the block's cells at once.
module model_extremes_cells
  use contactsep_kinds, only: wp
  use model_extremes_workspace, only: extremes_workspace, reserve_cells, &
      offer, tie, converged
  use model_extremes_bounds, only: add_modes, cell_bounds, end_bound, &
      polish, phi_low
  implicit none
  private
  public :: search_level, halve, quarter

  !> Cells with p_max r <= phi_polish are polished by Newton steps.
  real(wp), parameter :: phi_polish = 1.0_wp

contains

  !> Bound, offer, prune, polish and halve the level's cells (all slots).
  pure subroutine search_level(ws, slots, level)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots, level
    integer :: slot

    do slot = 1, slots
      ws%half_width(slot) = ws%tau(slot) * 0.5_wp**(level + 1)
    end do
    call arcs(ws, slots, level)
    call add_modes(ws, slots, level)
    call cell_bounds(ws, slots)
    call offer_cells(ws, slots)
    call select_cells(ws, slots, level)
    call next_chain(ws, slots, level + 1)
    call split_cells(ws, slots)
  end subroutine search_level

  !> The level's arcs per slot and mode: cos and sin of phi_j
  !> (a whole turn: -1 and 0), and 1 where the mode is low.
  pure subroutine arcs(ws, slots, level)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots, level
    integer :: j, slot, first, last
    real(wp) :: scale, chain_c, chain_s, reach
    logical :: whole

    ! every slot from the first to the last with cells (those between
    ! without cells too: no branch on the slot)
    call active_slots(ws, slots, first, last)
    scale = 0.5_wp**level
    do j = 1, size(ws%p, 2)
      do slot = first, last
        chain_c = ws%chain_c(slot, j)
        chain_s = ws%chain_s(slot, j)
        reach = ws%p(slot, j) * ws%half_width(slot)
        ! turns(quadrant, level) >= 2, without the floor
        whole = ws%quadrant(slot, j) * scale >= 2.0_wp
        ws%arc_c(slot, j) = merge(-1.0_wp, chain_c, whole)
        ws%arc_s(slot, j) = merge(0.0_wp, max(chain_s, 0.0_wp), whole)
        ws%low(slot, j) = merge(0.0_wp, merge(1.0_wp, 0.0_wp, &
            reach <= phi_low), whole)
      end do
    end do
  end subroutine arcs

  !> The half-angles of `level` from the level above's, for the designs
  !> with cells left (a loop over slots for each mode: contiguous, and
  !> vectorised; the other slots keep theirs).
  pure subroutine next_chain(ws, slots, level)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots, level
    real(wp) :: hc, hs, chain_c, chain_s, quadrant
    logical :: active
    integer :: j, slot, first, last

    call active_slots(ws, slots, first, last)
    do j = 1, size(ws%p, 2)
      do slot = first, last
        chain_c = ws%chain_c(slot, j)
        chain_s = ws%chain_s(slot, j)
        quadrant = ws%quadrant(slot, j)
        active = ws%cells_of(slot) > 0
        call halve(chain_c, chain_s, quarter(quadrant, level), hc, hs)
        ws%chain_c(slot, j) = merge(hc, chain_c, active)
        ws%chain_s(slot, j) = merge(hs, chain_s, active)
      end do
    end do
  end subroutine next_chain

  !> The first and last slots with cells (last < first when none).
  pure subroutine active_slots(ws, slots, first, last)
    type(extremes_workspace), intent(in) :: ws
    integer, intent(in) :: slots
    integer, intent(out) :: first, last

    first = 1
    do while (first <= slots)
      if (ws%cells_of(first) > 0) exit
      first = first + 1
    end do
    last = slots
    do while (last >= first)
      if (ws%cells_of(last) > 0) exit
      last = last - 1
    end do
  end subroutine active_slots

  !> cos and sin of phi/2 from those of phi, in the given quadrant.
  elemental subroutine halve(cos_phi, sin_phi, quadrant, cos_half, sin_half)
    real(wp), intent(in) :: cos_phi, sin_phi
    real(wp), intent(in) :: quadrant
    real(wp), intent(out) :: cos_half, sin_half
    real(wp) :: big, small
    logical :: up

    ! the larger of |cos phi/2| and |sin phi/2| by its square root (no
    ! cancellation), the other from sin phi = 2 cos phi/2 sin phi/2;
    ! branch-free, so that a loop of halvings vectorises
    up = cos_phi >= 0.0_wp
    big = sqrt(0.5_wp * (1.0_wp + abs(cos_phi)))
    small = abs(sin_phi) / (2.0_wp * big)
    cos_half = merge(big, small, up)
    sin_half = merge(small, big, up)
    cos_half = merge(-cos_half, cos_half, quadrant == 1.0_wp .or. &
        quadrant == 2.0_wp)
    sin_half = merge(-sin_half, sin_half, quadrant >= 2.0_wp)
  end subroutine halve

  !> floor(p_j tau/pi) / 2^level (given floor(p_j tau/pi)): the half-turns
  !> of p_j tau/2^(level+1).
  elemental function turns(quadrant, level) result(q)
    real(wp), intent(in) :: quadrant
    integer, intent(in) :: level
    real(wp) :: q

    q = whole_part(quadrant * 0.5_wp**level)
  end function turns

  !> The quadrant (0 to 3) of p_j tau/2^(level+1): the last two bits of its
  !> half-turns.
  elemental function quarter(quadrant, level) result(q)
    real(wp), intent(in) :: quadrant
    integer, intent(in) :: level
    real(wp) :: q, half_turns

    half_turns = turns(quadrant, level)
    q = half_turns - 4.0_wp * whole_part(0.25_wp * half_turns)
  end function quarter

  !> floor(x) for 0 <= x < 2^51 (floor(p_j tau/pi) < 2^52/pi: a design with
  !> p_max tau >= 2^52 is not searched), exact, without a branch or the
  !> SSE4.1 rounding instruction plain x86-64 lacks (so that the loops
  !> over slots vectorise): adding and taking away 2^52 rounds x to the
  !> nearest integer.
  elemental function whole_part(x) result(f)
    real(wp), intent(in) :: x
    real(wp) :: f
    real(wp), parameter :: two_52 = 2.0_wp**52

    f = (x + two_52) - two_52
    f = f - merge(1.0_wp, 0.0_wp, f > x)
  end function whole_part

  !> The cells' centres and certified points that come within the tie of
  !> their design's best, as candidates (the best values first raised to
  !> the level's, so that only points near them are kept).
  pure subroutine offer_cells(ws, slots)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots
    integer :: k, s, lo, hi
    real(wp) :: best_up, best_down, floor_up, floor_down

    ! a slot's cells at a time (contiguous), its best and floors scalars
    do s = 1, slots
      if (ws%cells_of(s) == 0) cycle
      lo = ws%first(s)
      hi = lo + ws%cells_of(s) - 1
      best_up = ws%best(1, s)
      best_down = ws%best(2, s)
      do k = lo, hi
        best_up = max(best_up, ws%value(k), ws%sure(k, 1))
        best_down = max(best_down, -ws%value(k), ws%sure(k, 2))
      end do
      ws%best(1, s) = best_up
      ws%best(2, s) = best_down
      floor_up = best_up - tie * ws%scale(s)
      floor_down = best_down - tie * ws%scale(s)
      ws%floor_value(1, s) = floor_up
      ws%floor_value(2, s) = floor_down
      do k = lo, hi
        if (max(ws%value(k), ws%sure(k, 1)) < floor_up .and. &
            max(-ws%value(k), ws%sure(k, 2)) < floor_down) cycle
        if (ws%value(k) >= floor_up) &
            call offer(ws, s, 1, ws%centre(k), ws%value(k))
        if (-ws%value(k) >= floor_down) &
            call offer(ws, s, 2, ws%centre(k), -ws%value(k))
        if (ws%sure(k, 1) >= floor_up) &
            call offer(ws, s, 1, ws%centre(k) + ws%sure_at(k, 1), &
            ws%sure(k, 1))
        if (ws%sure(k, 2) >= floor_down) &
            call offer(ws, s, 2, ws%centre(k) + ws%sure_at(k, 2), &
            ws%sure(k, 2))
      end do
    end do
  end subroutine offer_cells

  !> Drop, finish or polish each cell per side; ws%keep marks the cells to
  !> halve.  A design's cells are all halved while no mode resolves (its
  !> slowest mode turns more than half a turn over a cell).
  pure subroutine select_cells(ws, slots, level)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots, level
    real(wp) :: r, margin, hopeless
    logical :: done
    integer :: k, s, side, lo, hi

    do s = 1, slots
      ws%conv(s) = converged * ws%scale(s)
      if (ws%cells_of(s) == 0) cycle
      lo = ws%first(s)
      hi = lo + ws%cells_of(s) - 1
      if (turns(ws%min_quadrant(s), level) >= 2.0_wp) then
        ! nothing can be dropped or finished yet
        ws%floor_value(:, s) = -huge(1.0_wp)
        ws%conv(s) = -huge(1.0_wp)
        cycle
      end if
      r = ws%half_width(s)
      if (ws%all_low(s) > 0.0_wp) then
        ! the cells at the window's ends (a slot's cells are in time order)
        if (ws%centre(lo) - r <= 0.0_wp) call end_bound(ws, lo, 1, 0.0_wp, &
            2.0_wp * r)
        if (ws%centre(hi) + r >= ws%tau(s)) call end_bound(ws, hi, 3, &
            -2.0_wp * r, 0.0_wp)
      end if
      margin = (9.0_wp * (level + 1) + 2.0_wp * ws%n(s) + 8.0_wp) &
          * epsilon(1.0_wp) * ws%scale(s)
      ws%floor_value(:, s) = ws%floor_value(:, s) - margin
    end do
    call judge(ws%cells, ws%slot, ws%floor_value, ws%conv, ws%value, &
        ws%sure, ws%bound, ws%alive, ws%keep)
    ! the polishes after every cell is pruned (they raise the best); none
    ! where the side's curvature bound K has K r^2/2 > converged * S: the
    ! bound about any point of the cell then stays above its value by
    ! about that much (the cell is halved; skipping the three Newton
    ! steps changes no decision in the benchmark's designs)
    do s = 1, slots
      if (ws%cells_of(s) == 0) cycle
      r = ws%half_width(s)
      if (ws%p_max(s) * r > phi_polish) cycle
      lo = ws%first(s)
      hi = lo + ws%cells_of(s) - 1
      hopeless = converged * ws%scale(s)
      do k = lo, hi
        do side = 1, 2
          if (.not. ws%alive(k, side)) cycle
          if (merge(ws%curve_up(k), ws%curve_down(k), side == 1) &
              * (r * r * 0.5_wp) > hopeless) cycle
          call polish(ws, k, side, r, done)
          if (done) then
            ws%alive(k, side) = .false.
            ws%keep(k) = ws%alive(k, 1) .or. ws%alive(k, 2)
          end if
        end do
      end do
    end do
  end subroutine select_cells

  !> A cell stays alive on a side (1: y3, 2: -y3) while its bound there
  !> reaches its design's floor and is more than its conv above the larger
  !> of its value (with the side's sign) and its certified value; keep:
  !> alive on either side.  (Both sides in one pass over the cells.)
  pure subroutine judge(cells, slot, floor_value, conv, value, sure, bound, &
      alive, keep)
    integer, intent(in) :: cells, slot(:)
    real(wp), intent(in) :: floor_value(:, :), conv(:), value(:)
    real(wp), intent(in) :: sure(:, :), bound(:, :)
    logical, intent(inout) :: alive(:, :)
    logical, intent(out) :: keep(:)
    integer :: k, s

    do k = 1, cells
      s = slot(k)
      alive(k, 1) = alive(k, 1) .and. bound(k, 1) >= floor_value(1, s) &
          .and. bound(k, 1) - max(value(k), sure(k, 1)) > conv(s)
      alive(k, 2) = alive(k, 2) .and. bound(k, 2) >= floor_value(2, s) &
          .and. bound(k, 2) - max(-value(k), sure(k, 2)) > conv(s)
      keep(k) = alive(k, 1) .or. alive(k, 2)
    end do
  end subroutine judge

  !> Halve every kept cell: children offset by -+ r/2 (the cos and sin of
  !> p_j r/2 are the next level's chain), left and right side by side, each
  !> slot's children together.
  pure subroutine split_cells(ws, slots)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots
    real(wp), allocatable :: swap(:, :), swap_centre(:)
    logical, allocatable :: swap_alive(:, :)
    integer, allocatable :: swap_slot(:)
    integer :: kept, i, j, k, s, nm, out

    nm = size(ws%p, 2)
    kept = count(ws%keep(1:ws%cells))
    ws%cells_of(1:slots) = 0
    if (kept == 0) then
      ws%cells = 0
      return
    end if
    call reserve_cells(ws, 2 * kept, nm)
    kept = 0
    do k = 1, ws%cells
      if (ws%keep(k)) then
        kept = kept + 1
        ws%which(kept) = k
        s = ws%slot(k)
        ws%cells_of(s) = ws%cells_of(s) + 2
      end if
    end do
    ! the children of a slot follow its kept parents, in time order
    out = 1
    do s = 1, slots
      ws%first(s) = out
      out = out + ws%cells_of(s)
    end do
    do j = 1, nm
      call rotate_children(kept, ws%which, ws%slot, ws%chain_c(:, j), &
          ws%chain_s(:, j), ws%a(:, j), ws%b(:, j), ws%next_a(:, j), &
          ws%next_b(:, j))
    end do
    do i = 1, kept
      k = ws%which(i)
      s = ws%slot(k)
      out = 2 * i - 1
      ws%next_centre(out) = ws%centre(k) - 0.5_wp * ws%half_width(s)
      ws%next_centre(out + 1) = ws%centre(k) + 0.5_wp * ws%half_width(s)
      ws%next_alive(out, 1) = ws%alive(k, 1)
      ws%next_alive(out + 1, 1) = ws%alive(k, 1)
      ws%next_alive(out, 2) = ws%alive(k, 2)
      ws%next_alive(out + 1, 2) = ws%alive(k, 2)
      ws%next_slot(out) = s
      ws%next_slot(out + 1) = s
    end do
    ws%cells = 2 * kept
    ! the children become the current cells (the arrays swap roles)
    call move_alloc(ws%a, swap)
    call move_alloc(ws%next_a, ws%a)
    call move_alloc(swap, ws%next_a)
    call move_alloc(ws%b, swap)
    call move_alloc(ws%next_b, ws%b)
    call move_alloc(swap, ws%next_b)
    call move_alloc(ws%centre, swap_centre)
    call move_alloc(ws%next_centre, ws%centre)
    call move_alloc(swap_centre, ws%next_centre)
    call move_alloc(ws%alive, swap_alive)
    call move_alloc(ws%next_alive, ws%alive)
    call move_alloc(swap_alive, ws%next_alive)
    call move_alloc(ws%slot, swap_slot)
    call move_alloc(ws%next_slot, ws%slot)
    call move_alloc(swap_slot, ws%next_slot)
  end subroutine split_cells

  !> One mode's children: parent which(i) gives rows 2 i - 1 (left, its
  !> phase turned by -p h) and 2 i (right, +p h) of next_a, next_b; cx, sx
  !> = cos, sin of p h per design slot.  (Padded modes, zero, stay zero.)
  pure subroutine rotate_children(kept, which, slot, cx, sx, a, b, next_a, &
      next_b)
    integer, intent(in) :: kept, which(:), slot(:)
    real(wp), intent(in) :: cx(:), sx(:), a(:), b(:)
    real(wp), intent(inout) :: next_a(:), next_b(:)
    real(wp) :: a1, b1, c1, s1, a2, b2, c2, s2
    integer :: i, k1, k2

    ! two parents a step: the arithmetic on pairs (the loads are a gather,
    ! which plain x86-64 cannot vectorise)
    do i = 1, kept - 1, 2
      k1 = which(i)
      k2 = which(i + 1)
      c1 = cx(slot(k1))
      s1 = sx(slot(k1))
      c2 = cx(slot(k2))
      s2 = sx(slot(k2))
      a1 = a(k1)
      b1 = b(k1)
      a2 = a(k2)
      b2 = b(k2)
      next_a(2 * i - 1) = a1 * c1 - b1 * s1
      next_a(2 * i) = a1 * c1 + b1 * s1
      next_a(2 * i + 1) = a2 * c2 - b2 * s2
      next_a(2 * i + 2) = a2 * c2 + b2 * s2
      next_b(2 * i - 1) = b1 * c1 + a1 * s1
      next_b(2 * i) = b1 * c1 - a1 * s1
      next_b(2 * i + 1) = b2 * c2 + a2 * s2
      next_b(2 * i + 2) = b2 * c2 - a2 * s2
    end do
    if (mod(kept, 2) == 1) then
      k1 = which(kept)
      c1 = cx(slot(k1))
      s1 = sx(slot(k1))
      a1 = a(k1)
      b1 = b(k1)
      next_a(2 * kept - 1) = a1 * c1 - b1 * s1
      next_a(2 * kept) = a1 * c1 + b1 * s1
      next_b(2 * kept - 1) = b1 * c1 + a1 * s1
      next_b(2 * kept) = b1 * c1 - a1 * s1
    end if
  end subroutine rotate_children

end module model_extremes_cells
