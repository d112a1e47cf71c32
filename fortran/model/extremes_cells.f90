!> One level of the extremes search (model_extremes) on a block of designs:
!> every live cell bounded, its centre and certified points offered as
!> candidates, dropped, finished, polished or halved.
!>
!> On a cell of half-width r around m, with phi_j = p_j r, the modes with
!> phi_j > phi_low are bounded by their own maxima over the arc [p_j m -
!> phi_j, p_j m + phi_j] (|c_j| if it reaches the crest, else the larger
!> end), the others by Taylor's theorem: y_L(m + x) lies between
!> A + B x + K_lo x^2/2 and A + B x + K_up x^2/2, A and B their value and
!> slope at m, K_lo and K_up bounds of their second derivative on the cell
!> (p_j^2 times the arc maxima).  The upper parabola bounds the cell; the
!> top of the lower one is a certified value at a known point.  A cell at
!> an end of the window whose modes are all low is also bounded by Taylor
!> about that end.  Cells small enough (p_max r <= phi_polish) are polished:
!> Newton steps to the vertex, and a bound about it.
!>
!> Cells are vectors (contiguous, a design's together, in time order).  The
!> per-mode sums run a design at a time (its mode's data then scalars in
!> the loop); every other step runs over all the block's cells at once,
!> each design's scalars gathered by the cell's slot.
module model_extremes_cells
  use, intrinsic :: iso_fortran_env, only: int64
  use contactsep_kinds, only: wp
  implicit none
  private
  public :: reserve_slots, reserve_cells, search_level, halve, turns, &
      offer, earliest

  !> Two values closer than tie * S are a tie: the earlier is reported.
  real(wp), parameter, public :: tie = 1.0e-12_wp
  !> A cell is finished when its bound is within converged * S of a value
  !> it holds.
  real(wp), parameter, public :: converged = 0.25e-12_wp
  !> Modes with p_j r <= phi_low enter a cell's bound by Taylor's theorem.
  real(wp), parameter :: phi_low = 1.0_wp
  !> Cells with p_max r <= phi_polish are polished by Newton steps.
  real(wp), parameter :: phi_polish = 1.0_wp
  !> Newton steps of a polish.
  integer, parameter :: polish_steps = 3

  !> Working arrays kept between blocks and batches (grown as needed).
  type, public :: extremes_workspace
    !> Per design slot and mode: p_j, c_j, |c_j|, cos and sin of p_j tau/2,
    !> floor(p_j tau/pi), and cos and sin of p_j r of the current level.
    real(wp), allocatable :: p(:, :), c(:, :), absc(:, :), cos0(:, :)
    real(wp), allocatable :: sin0(:, :), chain_c(:, :), chain_s(:, :)
    integer(int64), allocatable :: quadrant(:, :)
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
    integer(int64), allocatable :: min_quadrant(:), work(:)
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

  !> cos and sin of phi/2 from those of phi, in the given quadrant.
  elemental subroutine halve(cos_phi, sin_phi, quadrant, cos_half, sin_half)
    real(wp), intent(in) :: cos_phi, sin_phi
    integer(int64), intent(in) :: quadrant
    real(wp), intent(out) :: cos_half, sin_half
    real(wp) :: hc, hs

    if (cos_phi >= 0.0_wp) then
      hc = sqrt(0.5_wp * (1.0_wp + cos_phi))
      hs = abs(sin_phi) / (2.0_wp * hc)
    else
      hs = sqrt(0.5_wp * (1.0_wp - cos_phi))
      hc = abs(sin_phi) / (2.0_wp * hs)
    end if
    cos_half = merge(-hc, hc, quadrant == 1 .or. quadrant == 2)
    sin_half = merge(-hs, hs, quadrant >= 2)
  end subroutine halve

  !> floor(p_j tau/pi) / 2^level: the half-turns of p_j tau/2^(level+1);
  !> its last two bits are that angle's quadrant.
  elemental function turns(quadrant, level) result(q)
    integer(int64), intent(in) :: quadrant
    integer, intent(in) :: level
    integer(int64) :: q

    q = shiftr(quadrant, min(level, 63))
  end function turns

  !> Bound, offer, prune, polish and halve the level's cells (all slots).
  pure subroutine search_level(ws, slots, level)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots, level
    integer :: slot, cells

    cells = ws%cells
    do slot = 1, slots
      ws%half_width(slot) = ws%tau(slot) * 0.5_wp**(level + 1)
    end do
    call arcs(ws, slots, level)
    call add_modes(ws, slots, level)
    call cell_bounds(ws, slots)
    call offer_cells(ws, slots)
    call select_cells(ws, slots, level)
    ! the next level's half-angles (of designs with cells left), then the
    ! children
    do slot = 1, slots
      if (ws%cells_of(slot) == 0) cycle
      call halve(ws%chain_c(slot, :), ws%chain_s(slot, :), &
          iand(turns(ws%quadrant(slot, :), level + 1), 3_int64), &
          ws%arc_c(slot, :), ws%arc_s(slot, :))
      ws%chain_c(slot, :) = ws%arc_c(slot, :)
      ws%chain_s(slot, :) = ws%arc_s(slot, :)
    end do
    call split_cells(ws, slots)
  end subroutine search_level

  !> The level's arcs per slot (with cells) and mode: cos and sin of phi_j
  !> (a whole turn: -1 and 0), and 1 where the mode is low.
  pure subroutine arcs(ws, slots, level)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots, level
    integer :: j, slot
    logical :: whole

    do j = 1, size(ws%p, 2)
      do slot = 1, slots
        if (ws%cells_of(slot) == 0) cycle
        whole = turns(ws%quadrant(slot, j), level) >= 2
        ws%arc_c(slot, j) = merge(-1.0_wp, ws%chain_c(slot, j), whole)
        ws%arc_s(slot, j) = merge(0.0_wp, max(ws%chain_s(slot, j), &
            0.0_wp), whole)
        ws%low(slot, j) = merge(1.0_wp, 0.0_wp, .not. whole .and. &
            ws%p(slot, j) * ws%half_width(slot) <= phi_low)
      end do
    end do
  end subroutine arcs

  !> Each cell's value, low-mode sums and high-mode arc maxima (a slot's
  !> cells at a time: its modes' data are scalars there).  A mode whose arc
  !> is a whole turn adds |c| to every cell's high sums (ws%whole).
  pure subroutine add_modes(ws, slots, level)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots, level
    integer :: j, s, lo, hi, cells

    cells = ws%cells
    ws%value(1:cells) = 0.0_wp
    ws%a_low(1:cells) = 0.0_wp
    ws%slope(1:cells) = 0.0_wp
    ws%curve_up(1:cells) = 0.0_wp
    ws%curve_down(1:cells) = 0.0_wp
    ws%high_up(1:cells) = 0.0_wp
    ws%high_down(1:cells) = 0.0_wp
    ws%whole(1:slots) = 0.0_wp
    do s = 1, slots
      if (ws%cells_of(s) == 0) cycle
      lo = ws%first(s)
      hi = lo + ws%cells_of(s) - 1
      do j = 1, ws%n(s)
        if (ws%arc_c(s, j) == -1.0_wp .and. ws%arc_s(s, j) == 0.0_wp) then
          ws%whole(s) = ws%whole(s) + ws%absc(s, j)
          ws%value(lo:hi) = ws%value(lo:hi) + ws%a(lo:hi, j)
        else if (ws%low(s, j) > 0.0_wp) then
          call add_low(hi - lo + 1, ws%a(lo:hi, j), ws%b(lo:hi, j), &
              ws%absc(s, j), ws%arc_c(s, j), ws%arc_s(s, j), ws%p(s, j), &
              ws%value(lo:hi), ws%a_low(lo:hi), ws%slope(lo:hi), &
              ws%curve_up(lo:hi), ws%curve_down(lo:hi))
        else
          call add_high(hi - lo + 1, ws%a(lo:hi, j), ws%b(lo:hi, j), &
              ws%absc(s, j), ws%arc_c(s, j), ws%arc_s(s, j), &
              ws%value(lo:hi), ws%high_up(lo:hi), ws%high_down(lo:hi))
        end if
      end do
    end do
  end subroutine add_modes

  !> The maxima of c sin and -c sin over a cell's arc (absc = |c|; ca, sa
  !> = cos, sin of the arc's half-width): |c| if the arc reaches the crest,
  !> else its larger end.
  elemental subroutine arc_maxima(a, b, absc, ca, sa, up, down)
    real(wp), intent(in) :: a, b
    real(wp), value :: absc, ca, sa
    real(wp), intent(out) :: up, down

    real(wp) :: ab

    ! (written as max() with a merge of constants so that the vectoriser
    ! need not load b inside a branch)
    ab = abs(b)
    up = max(a * ca + ab * sa, merge(absc, -huge(absc), a >= absc * ca))
    down = max(ab * sa - a * ca, merge(absc, -huge(absc), -a >= absc * ca))
  end subroutine arc_maxima

  !> A mode bounded by Taylor's theorem: its share of the cells' value,
  !> slope and curvature bounds (p^2 times its arc maxima of -+ c sin).
  pure subroutine add_low(cells, a, b, absc, ca, sa, p, value, a_low, &
      slope, curve_up, curve_down)
    integer, intent(in) :: cells
    real(wp), intent(in) :: a(cells), b(cells)
    real(wp), value :: absc, ca, sa, p
    real(wp), intent(inout) :: value(cells), a_low(cells), slope(cells)
    real(wp), intent(inout) :: curve_up(cells), curve_down(cells)
    real(wp) :: up, down, p2
    integer :: k

    p2 = p * p
    do k = 1, cells
      call arc_maxima(a(k), b(k), absc, ca, sa, up, down)
      value(k) = value(k) + a(k)
      a_low(k) = a_low(k) + a(k)
      slope(k) = slope(k) + p * b(k)
      curve_up(k) = curve_up(k) + p2 * down
      curve_down(k) = curve_down(k) + p2 * up
    end do
  end subroutine add_low

  !> A mode bounded by its own arc maxima.
  pure subroutine add_high(cells, a, b, absc, ca, sa, value, high_up, &
      high_down)
    integer, intent(in) :: cells
    real(wp), intent(in) :: a(cells), b(cells)
    real(wp), value :: absc, ca, sa
    real(wp), intent(inout) :: value(cells), high_up(cells)
    real(wp), intent(inout) :: high_down(cells)
    real(wp) :: up, down
    integer :: k

    do k = 1, cells
      call arc_maxima(a(k), b(k), absc, ca, sa, up, down)
      value(k) = value(k) + a(k)
      high_up(k) = high_up(k) + up
      high_down(k) = high_down(k) + down
    end do
  end subroutine add_high

  !> Each cell's bounds of y3 and -y3 (the upper Taylor parabolas' maxima
  !> plus the high modes' arc maxima) and, where every mode of its design
  !> is low, its certified values (the lower parabolas' tops) with their
  !> offsets from the centre (else -huge: with high modes at their least
  !> they would not help).
  pure subroutine cell_bounds(ws, slots)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots
    integer :: s

    do s = 1, slots
      ws%all_low(s) = merge(1.0_wp, 0.0_wp, &
          ws%p_max(s) * ws%half_width(s) <= phi_low)
    end do
    call bounds_kernel(ws%cells, ws%slot, ws%half_width, ws%all_low, &
        ws%whole, ws%a_low, ws%slope, ws%curve_up, ws%curve_down, &
        ws%high_up, ws%high_down, ws%bound(:, 1), ws%bound(:, 2), &
        ws%sure(:, 1), ws%sure(:, 2), ws%sure_at(:, 1), ws%sure_at(:, 2))
  end subroutine cell_bounds

  pure subroutine bounds_kernel(cells, slot, half_width, all_low, whole, &
      a, b, curve_up, curve_down, high_up, high_down, bound_up, &
      bound_down, sure_up, sure_down, at_up, at_down)
    integer, intent(in) :: cells, slot(:)
    real(wp), intent(in) :: half_width(:), all_low(:), whole(:)
    real(wp), intent(in) :: a(:), b(:), curve_up(:), curve_down(:)
    real(wp), intent(in) :: high_up(:), high_down(:)
    real(wp), intent(out) :: bound_up(:), bound_down(:), sure_up(:)
    real(wp), intent(out) :: sure_down(:), at_up(:), at_down(:)
    real(wp) :: r, lowest
    integer :: k

    do k = 1, cells
      r = half_width(slot(k))
      bound_up(k) = high_up(k) + whole(slot(k)) + parabola_max(a(k), &
          b(k), curve_up(k), -r, r)
      bound_down(k) = high_down(k) + whole(slot(k)) + parabola_max(-a(k), &
          -b(k), curve_down(k), -r, r)
      ! the lower parabolas a + b x - curve_down x^2/2 (y3) and
      ! -a - b x - curve_up x^2/2 (-y3): their tops on [-r, r], where
      ! every mode is low (else -huge)
      lowest = merge(-huge(1.0_wp), huge(1.0_wp), all_low(slot(k)) == 0.0_wp)
      sure_up(k) = min(parabola_max(a(k), b(k), -curve_down(k), -r, r), &
          lowest)
      at_up(k) = parabola_at(b(k), -curve_down(k), r)
      sure_down(k) = min(parabola_max(-a(k), -b(k), -curve_up(k), -r, r), &
          lowest)
      at_down(k) = parabola_at(-b(k), -curve_up(k), r)
    end do
  end subroutine bounds_kernel

  !> max of a + b x + k x^2/2 over lo <= x <= hi.
  elemental function parabola_max(a, b, k, lo, hi) result(top)
    real(wp), intent(in) :: a, b, k, lo, hi
    real(wp) :: top, x

    top = max(a + b * lo + 0.5_wp * k * lo * lo, &
        a + b * hi + 0.5_wp * k * hi * hi)
    ! the vertex, where the parabola opens downwards (clipped to the ends)
    x = min(max(-b / min(k, -tiny(k)), lo), hi)
    top = merge(max(top, a + b * x + 0.5_wp * k * x * x), top, k < 0.0_wp)
  end function parabola_max

  !> Where a + b x + k x^2/2 is largest on -r <= x <= r (the vertex when
  !> the parabola opens downwards, else the higher end; -r of equal ends).
  elemental function parabola_at(b, k, r) result(x)
    real(wp), intent(in) :: b, k, r
    real(wp) :: x

    ! the ends differ by 2 b r: the right one is higher where b > 0
    x = merge(min(max(-b / min(k, -tiny(k)), -r), r), &
        merge(r, -r, b > 0.0_wp), k < 0.0_wp)
  end function parabola_at

  !> The cells' centres and certified points that come within the tie of
  !> their design's best, as candidates (the best values first raised to
  !> the level's, so that only points near them are kept).
  pure subroutine offer_cells(ws, slots)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots
    integer :: k, s

    do k = 1, ws%cells
      s = ws%slot(k)
      ws%best(1, s) = max(ws%best(1, s), ws%value(k), ws%sure(k, 1))
      ws%best(2, s) = max(ws%best(2, s), -ws%value(k), ws%sure(k, 2))
    end do
    do s = 1, slots
      ws%floor_value(:, s) = ws%best(:, s) - tie * ws%scale(s)
    end do
    call near_best(ws%cells, ws%slot, ws%floor_value, ws%value, &
        ws%sure(:, 1), ws%sure(:, 2), ws%keep)
    do k = 1, ws%cells
      if (.not. ws%keep(k)) cycle
      s = ws%slot(k)
      if (ws%value(k) >= ws%floor_value(1, s)) &
          call offer(ws, s, 1, ws%centre(k), ws%value(k))
      if (-ws%value(k) >= ws%floor_value(2, s)) &
          call offer(ws, s, 2, ws%centre(k), -ws%value(k))
      if (ws%sure(k, 1) >= ws%floor_value(1, s)) &
          call offer(ws, s, 1, ws%centre(k) + ws%sure_at(k, 1), &
          ws%sure(k, 1))
      if (ws%sure(k, 2) >= ws%floor_value(2, s)) &
          call offer(ws, s, 2, ws%centre(k) + ws%sure_at(k, 2), &
          ws%sure(k, 2))
    end do
  end subroutine offer_cells

  !> Cells whose value, or certified value, reaches their design's floors.
  pure subroutine near_best(cells, slot, floor_value, value, sure_up, &
      sure_down, near)
    integer, intent(in) :: cells, slot(:)
    real(wp), intent(in) :: floor_value(:, :), value(:), sure_up(:)
    real(wp), intent(in) :: sure_down(:)
    logical, intent(out) :: near(:)
    integer :: k

    do k = 1, cells
      near(k) = max(value(k), sure_up(k)) >= floor_value(1, slot(k)) &
          .or. max(-value(k), sure_down(k)) >= floor_value(2, slot(k))
    end do
  end subroutine near_best

  !> Drop, finish or polish each cell per side; ws%keep marks the cells to
  !> halve.  A design's cells are all halved while no mode resolves (its
  !> slowest mode turns more than half a turn over a cell).
  pure subroutine select_cells(ws, slots, level)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: slots, level
    real(wp) :: r, margin
    logical :: done
    integer :: k, s, side, lo, hi

    do s = 1, slots
      ws%conv(s) = converged * ws%scale(s)
      if (ws%cells_of(s) == 0) cycle
      lo = ws%first(s)
      hi = lo + ws%cells_of(s) - 1
      if (turns(ws%min_quadrant(s), level) >= 2) then
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
    call judge(ws%cells, ws%slot, 1.0_wp, ws%floor_value(1, :), ws%conv, &
        ws%value, ws%sure(:, 1), ws%bound(:, 1), ws%alive(:, 1))
    call judge(ws%cells, ws%slot, -1.0_wp, ws%floor_value(2, :), ws%conv, &
        ws%value, ws%sure(:, 2), ws%bound(:, 2), ws%alive(:, 2))
    ! the polishes after every cell is pruned (they raise the best)
    do s = 1, slots
      if (ws%cells_of(s) == 0) cycle
      r = ws%half_width(s)
      if (ws%p_max(s) * r > phi_polish) cycle
      lo = ws%first(s)
      hi = lo + ws%cells_of(s) - 1
      do k = lo, hi
        do side = 1, 2
          if (.not. ws%alive(k, side)) cycle
          call polish(ws, k, side, r, done)
          if (done) ws%alive(k, side) = .false.
        end do
      end do
    end do
    ws%keep(1:ws%cells) = ws%alive(1:ws%cells, 1) .or. &
        ws%alive(1:ws%cells, 2)
  end subroutine select_cells

  !> A side's cells stay alive while their bound reaches their design's
  !> floor and is more than its conv above the larger of their value
  !> (times sgn) and their certified value.
  pure subroutine judge(cells, slot, sgn, floor_value, conv, value, sure, &
      bound, alive)
    integer, intent(in) :: cells, slot(:)
    real(wp), intent(in) :: sgn, floor_value(:), conv(:), value(:)
    real(wp), intent(in) :: sure(:), bound(:)
    logical, intent(inout) :: alive(:)
    integer :: k

    do k = 1, cells
      alive(k) = alive(k) .and. bound(k) >= floor_value(slot(k)) .and. &
          bound(k) - max(sgn * value(k), sure(k)) > conv(slot(k))
    end do
  end subroutine judge

  !> Cell k at t = 0 (at = 1) or t = tau (at = 3), its modes all low, is
  !> bounded by Taylor about that end too (offsets lo..hi from it), where
  !> y3 and its slope are known, and holds the end's value.
  pure subroutine end_bound(ws, k, at, lo, hi)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: k, at
    real(wp), intent(in) :: lo, hi
    real(wp) :: sgn, y_end, curve_side
    integer :: s, side

    s = ws%slot(k)
    do side = 1, 2
      sgn = merge(1.0_wp, -1.0_wp, side == 1)
      y_end = sgn * ws%ends(at, s)
      curve_side = merge(ws%curve_up(k), ws%curve_down(k), side == 1)
      ws%bound(k, side) = min(ws%bound(k, side), parabola_max(y_end, &
          sgn * ws%ends(at + 1, s), curve_side, lo, hi))
      ws%sure(k, side) = max(ws%sure(k, side), y_end)
    end do
  end subroutine end_bound

  !> Newton steps (at most polish_steps) from cell k's centre to the vertex
  !> of y3's Taylor parabola; the point is offered, and done is true when
  !> the bound around it (the side's curvature bound on the cell) is
  !> within converged * S of its value.
  pure subroutine polish(ws, k, side, r, done)
    type(extremes_workspace), intent(inout) :: ws
    integer, intent(in) :: k, side
    real(wp), intent(in) :: r
    logical, intent(out) :: done
    real(wp) :: shift, x, x2, sx, cx, a2, b2, value, slope, second, sgn, pj
    real(wp) :: curve_bound
    integer :: j, step, s

    done = .false.
    s = ws%slot(k)
    sgn = merge(1.0_wp, -1.0_wp, side == 1)
    curve_bound = merge(ws%curve_up(k), ws%curve_down(k), side == 1)
    slope = ws%slope(k)
    second = 0.0_wp
    do j = 1, ws%n(s)
      second = second - ws%p(s, j)**2 * ws%a(k, j)
    end do
    shift = 0.0_wp
    value = 0.0_wp
    do step = 1, polish_steps
      if (.not. (sgn * second < 0.0_wp)) return
      shift = shift - slope / second
      if (.not. (abs(shift) <= r)) return
      value = 0.0_wp
      slope = 0.0_wp
      second = 0.0_wp
      do j = 1, ws%n(s)
        ! |x| <= p_max r <= 1: Taylor to x^19 and x^20 is exact to rounding
        pj = ws%p(s, j)
        x = pj * shift
        x2 = x * x
        sx = x * (1.0_wp - x2 / 6.0_wp * (1.0_wp - x2 / 20.0_wp * (1.0_wp &
            - x2 / 42.0_wp * (1.0_wp - x2 / 72.0_wp * (1.0_wp - x2 &
            / 110.0_wp * (1.0_wp - x2 / 156.0_wp * (1.0_wp - x2 / 210.0_wp &
            * (1.0_wp - x2 / 272.0_wp * (1.0_wp - x2 / 342.0_wp)))))))))
        cx = 1.0_wp - x2 / 2.0_wp * (1.0_wp - x2 / 12.0_wp * (1.0_wp - x2 &
            / 30.0_wp * (1.0_wp - x2 / 56.0_wp * (1.0_wp - x2 / 90.0_wp &
            * (1.0_wp - x2 / 132.0_wp * (1.0_wp - x2 / 182.0_wp * (1.0_wp &
            - x2 / 240.0_wp * (1.0_wp - x2 / 306.0_wp * (1.0_wp - x2 &
            / 380.0_wp)))))))))
        a2 = ws%a(k, j) * cx + ws%b(k, j) * sx
        b2 = ws%b(k, j) * cx - ws%a(k, j) * sx
        value = value + a2
        slope = slope + pj * b2
        second = second - pj * pj * a2
      end do
    end do
    call offer(ws, s, side, ws%centre(k) + shift, sgn * value)
    done = parabola_max(sgn * value, sgn * slope, curve_bound, -r - shift, &
        r - shift) - sgn * value <= converged * ws%scale(s)
  end subroutine polish

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
    real(wp) :: aj, bj, c, s
    integer :: i, k

    do i = 1, kept
      k = which(i)
      c = cx(slot(k))
      s = sx(slot(k))
      aj = a(k)
      bj = b(k)
      next_a(2 * i - 1) = aj * c - bj * s
      next_b(2 * i - 1) = bj * c + aj * s
      next_a(2 * i) = aj * c + bj * s
      next_b(2 * i) = bj * c - aj * s
    end do
  end subroutine rotate_children

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

end module model_extremes_cells
