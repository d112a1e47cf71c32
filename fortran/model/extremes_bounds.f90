!> The bounds of the extremes search's cells (model_extremes_cells):
!> every live cell's value, its bounds of y3 and -y3 and, where every mode
!> is low, its certified values.
!>
!> On a cell of half-width r around m, with phi_j = p_j r, the modes with
!> phi_j > phi_low are bounded by their own maxima over the arc [p_j m -
!> phi_j, p_j m + phi_j] (|c_j| if it reaches the crest, else the larger
!> end), the others by Taylor's theorem: y_L(m + x) lies between
!> A + B x + K_lo x^2/2 and A + B x + K_up x^2/2, A and B their value and
!> slope at m, K_lo and K_up bounds of their second derivative on the cell
!> (p_j^2 times the arc maxima).  The upper parabola bounds the cell; the
!> top of the lower one is a certified value at a known point.
!>
!> A cell at an end of the window whose modes are all low is also bounded
!> by Taylor about that end (end_bound).  A small cell is polished: Newton
!> steps to the vertex of y3's Taylor parabola, and a bound about it.
!>
!> The per-mode sums and the bounds run a design at a time (its modes'
!> data then scalars in the loops).
module model_extremes_bounds
  use contactsep_kinds, only: wp
  use model_extremes_workspace, only: extremes_workspace, offer, converged
  implicit none
  private
  public :: add_modes, cell_bounds, end_bound, polish

  !> Modes with p_j r <= phi_low enter a cell's bound by Taylor's theorem.
  real(wp), parameter, public :: phi_low = 1.0_wp
  !> Newton steps of a polish.
  integer, parameter :: polish_steps = 3
  !> The polish's Taylor factors of sin and cos, 1/((2k)(2k+1)) and
  !> 1/((2k-1)(2k)): multiplied, not divided (a division costs several
  !> multiplications; each factor is rounded once, as the quotient was).
  real(wp), parameter :: inv_sin(9) = 1.0_wp / [6.0_wp, 20.0_wp, 42.0_wp, &
      72.0_wp, 110.0_wp, 156.0_wp, 210.0_wp, 272.0_wp, 342.0_wp]
  real(wp), parameter :: inv_cos(10) = 1.0_wp / [2.0_wp, 12.0_wp, 30.0_wp, &
      56.0_wp, 90.0_wp, 132.0_wp, 182.0_wp, 240.0_wp, 306.0_wp, 380.0_wp]

contains

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
      j = 0
      do while (j < ws%n(s))
        j = j + 1
        if (whole_turn(ws, s, j) .and. whole_turn(ws, s, j + 1)) then
          ! two whole-turn modes in one pass (their values only)
          ws%whole(s) = ws%whole(s) + ws%absc(s, j) + ws%absc(s, j + 1)
          ws%value(lo:hi) = ws%value(lo:hi) + (ws%a(lo:hi, j) &
              + ws%a(lo:hi, j + 1))
          j = j + 1
        else if (whole_turn(ws, s, j)) then
          ws%whole(s) = ws%whole(s) + ws%absc(s, j)
          ws%value(lo:hi) = ws%value(lo:hi) + ws%a(lo:hi, j)
        else if (low_mode(ws, s, j) .and. low_mode(ws, s, j + 1)) then
          ! two low modes in one pass over the cells (their five sums read
          ! and written once)
          call add_low_pair(hi - lo + 1, ws%a(lo:hi, j), ws%b(lo:hi, j), &
              ws%a(lo:hi, j + 1), ws%b(lo:hi, j + 1), ws%absc(s, j), &
              ws%arc_c(s, j), ws%arc_s(s, j), ws%p(s, j), &
              ws%absc(s, j + 1), ws%arc_c(s, j + 1), ws%arc_s(s, j + 1), &
              ws%p(s, j + 1), ws%value(lo:hi), ws%a_low(lo:hi), &
              ws%slope(lo:hi), ws%curve_up(lo:hi), ws%curve_down(lo:hi))
          j = j + 1
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

  !> Whether mode j of slot s (if it has one) is low (Taylor) on the
  !> level's cells.
  pure logical function low_mode(ws, s, j)
    type(extremes_workspace), intent(in) :: ws
    integer, intent(in) :: s, j

    low_mode = .false.
    if (j > ws%n(s)) return
    low_mode = ws%low(s, j) > 0.0_wp .and. .not. whole_turn(ws, s, j)
  end function low_mode

  !> Whether mode j of slot s (if it has one) turns a whole turn over the
  !> level's cells.
  pure logical function whole_turn(ws, s, j)
    type(extremes_workspace), intent(in) :: ws
    integer, intent(in) :: s, j

    whole_turn = .false.
    if (j > ws%n(s)) return
    whole_turn = ws%arc_c(s, j) == -1.0_wp .and. ws%arc_s(s, j) == 0.0_wp
  end function whole_turn

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

  !> Two modes bounded by Taylor's theorem (add_low), in one pass.
  pure subroutine add_low_pair(cells, a1, b1, a2, b2, absc1, ca1, sa1, p1, &
      absc2, ca2, sa2, p2, value, a_low, slope, curve_up, curve_down)
    integer, intent(in) :: cells
    real(wp), intent(in) :: a1(cells), b1(cells), a2(cells), b2(cells)
    real(wp), value :: absc1, ca1, sa1, p1, absc2, ca2, sa2, p2
    real(wp), intent(inout) :: value(cells), a_low(cells), slope(cells)
    real(wp), intent(inout) :: curve_up(cells), curve_down(cells)
    real(wp) :: up1, down1, up2, down2, p1_2, p2_2
    integer :: k

    p1_2 = p1 * p1
    p2_2 = p2 * p2
    do k = 1, cells
      call arc_maxima(a1(k), b1(k), absc1, ca1, sa1, up1, down1)
      call arc_maxima(a2(k), b2(k), absc2, ca2, sa2, up2, down2)
      value(k) = value(k) + (a1(k) + a2(k))
      a_low(k) = a_low(k) + (a1(k) + a2(k))
      slope(k) = slope(k) + (p1 * b1(k) + p2 * b2(k))
      curve_up(k) = curve_up(k) + (p1_2 * down1 + p2_2 * down2)
      curve_down(k) = curve_down(k) + (p1_2 * up1 + p2_2 * up2)
    end do
  end subroutine add_low_pair

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
    integer :: s, lo, hi

    ! a slot's cells at a time, its scalars there (no gather: the loop
    ! vectorises)
    do s = 1, slots
      ws%all_low(s) = merge(1.0_wp, 0.0_wp, &
          ws%p_max(s) * ws%half_width(s) <= phi_low)
      if (ws%cells_of(s) == 0) cycle
      lo = ws%first(s)
      hi = lo + ws%cells_of(s) - 1
      if (ws%all_low(s) > 0.0_wp) then
        call bounds_kernel(hi - lo + 1, ws%half_width(s), ws%whole(s), &
            ws%a_low(lo:hi), ws%slope(lo:hi), ws%curve_up(lo:hi), &
            ws%curve_down(lo:hi), ws%high_up(lo:hi), ws%high_down(lo:hi), &
            ws%bound(lo:hi, 1), ws%bound(lo:hi, 2), ws%sure(lo:hi, 1), &
            ws%sure(lo:hi, 2), ws%sure_at(lo:hi, 1), ws%sure_at(lo:hi, 2))
      else
        call upper_bounds(hi - lo + 1, ws%half_width(s), ws%whole(s), &
            ws%a_low(lo:hi), ws%slope(lo:hi), ws%curve_up(lo:hi), &
            ws%curve_down(lo:hi), ws%high_up(lo:hi), ws%high_down(lo:hi), &
            ws%bound(lo:hi, 1), ws%bound(lo:hi, 2))
        ws%sure(lo:hi, :) = -huge(1.0_wp)
        ws%sure_at(lo:hi, :) = 0.0_wp
      end if
    end do
  end subroutine cell_bounds

  !> The bounds of a slot's cells (half-width r, whole-turn modes' sum
  !> whole) where some mode is not low: no certified values.
  pure subroutine upper_bounds(cells, r, whole, a, b, curve_up, &
      curve_down, high_up, high_down, bound_up, bound_down)
    integer, intent(in) :: cells
    real(wp), value :: r, whole
    real(wp), intent(in) :: a(cells), b(cells), curve_up(cells)
    real(wp), intent(in) :: curve_down(cells), high_up(cells)
    real(wp), intent(in) :: high_down(cells)
    real(wp), intent(out) :: bound_up(cells), bound_down(cells)
    integer :: k

    do k = 1, cells
      bound_up(k) = high_up(k) + whole + parabola_top(a(k), b(k), &
          curve_up(k), -b(k) / min(curve_up(k), -tiny(1.0_wp)), -r, r)
      bound_down(k) = high_down(k) + whole + parabola_top(-a(k), -b(k), &
          curve_down(k), b(k) / min(curve_down(k), -tiny(1.0_wp)), -r, r)
    end do
  end subroutine upper_bounds

  !> The bounds of a slot's cells (half-width r, whole-turn modes' sum
  !> whole) where every mode is low, and their certified values.
  pure subroutine bounds_kernel(cells, r, whole, a, b, curve_up, &
      curve_down, high_up, high_down, bound_up, bound_down, sure_up, &
      sure_down, at_up, at_down)
    integer, intent(in) :: cells
    real(wp), value :: r, whole
    real(wp), intent(in) :: a(cells), b(cells), curve_up(cells)
    real(wp), intent(in) :: curve_down(cells), high_up(cells)
    real(wp), intent(in) :: high_down(cells)
    real(wp), intent(out) :: bound_up(cells), bound_down(cells)
    real(wp), intent(out) :: sure_up(cells), sure_down(cells)
    real(wp), intent(out) :: at_up(cells), at_down(cells)
    real(wp) :: vertex_up, vertex_down
    integer :: k

    do k = 1, cells
      ! two vertices serve the four parabolas: a + b x + curve_up x^2/2
      ! and -a - b x - curve_up x^2/2 turn at -b/curve_up, the other two
      ! at b/curve_down (each used only where its parabola opens
      ! downwards, so never where its curvature is zero)
      vertex_up = -b(k) / merge(curve_up(k), 1.0_wp, curve_up(k) /= 0.0_wp)
      vertex_down = b(k) / merge(curve_down(k), 1.0_wp, &
          curve_down(k) /= 0.0_wp)
      bound_up(k) = high_up(k) + whole + parabola_top(a(k), b(k), &
          curve_up(k), vertex_up, -r, r)
      bound_down(k) = high_down(k) + whole + parabola_top(-a(k), -b(k), &
          curve_down(k), vertex_down, -r, r)
      ! the lower parabolas a + b x - curve_down x^2/2 (y3) and
      ! -a - b x - curve_up x^2/2 (-y3): their tops on [-r, r]
      sure_up(k) = parabola_top(a(k), b(k), -curve_down(k), vertex_down, &
          -r, r)
      at_up(k) = parabola_at(b(k), -curve_down(k), vertex_down, r)
      sure_down(k) = parabola_top(-a(k), -b(k), -curve_up(k), vertex_up, &
          -r, r)
      at_down(k) = parabola_at(-b(k), -curve_up(k), vertex_up, r)
    end do
  end subroutine bounds_kernel

  !> max of a + b x + k x^2/2 over lo <= x <= hi.
  elemental function parabola_max(a, b, k, lo, hi) result(top)
    real(wp), intent(in) :: a, b, k, lo, hi
    real(wp) :: top

    top = parabola_top(a, b, k, -b / min(k, -tiny(k)), lo, hi)
  end function parabola_max

  !> max of a + b x + k x^2/2 over lo <= x <= hi, given its vertex -b/k
  !> where k < 0 (else not used).
  elemental function parabola_top(a, b, k, vertex, lo, hi) result(top)
    real(wp), intent(in) :: a, b, k, vertex, lo, hi
    real(wp) :: top, x

    top = max(a + b * lo + 0.5_wp * k * lo * lo, &
        a + b * hi + 0.5_wp * k * hi * hi)
    ! the vertex, where the parabola opens downwards (clipped to the ends)
    x = min(max(vertex, lo), hi)
    top = merge(max(top, a + b * x + 0.5_wp * k * x * x), top, k < 0.0_wp)
  end function parabola_top

  !> Where a + b x + k x^2/2 is largest on -r <= x <= r (the vertex, given
  !> as for parabola_top, when the parabola opens downwards, else the
  !> higher end; -r of equal ends).
  elemental function parabola_at(b, k, vertex, r) result(x)
    real(wp), intent(in) :: b, k, vertex, r
    real(wp) :: x

    ! the ends differ by 2 b r: the right one is higher where b > 0
    x = merge(min(max(vertex, -r), r), merge(r, -r, b > 0.0_wp), &
        k < 0.0_wp)
  end function parabola_at

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
        sx = x * (1.0_wp - x2 * inv_sin(1) * (1.0_wp - x2 * inv_sin(2) &
            * (1.0_wp - x2 * inv_sin(3) * (1.0_wp - x2 * inv_sin(4) &
            * (1.0_wp - x2 * inv_sin(5) * (1.0_wp - x2 * inv_sin(6) &
            * (1.0_wp - x2 * inv_sin(7) * (1.0_wp - x2 * inv_sin(8) &
            * (1.0_wp - x2 * inv_sin(9))))))))))
        cx = 1.0_wp - x2 * inv_cos(1) * (1.0_wp - x2 * inv_cos(2) &
            * (1.0_wp - x2 * inv_cos(3) * (1.0_wp - x2 * inv_cos(4) &
            * (1.0_wp - x2 * inv_cos(5) * (1.0_wp - x2 * inv_cos(6) &
            * (1.0_wp - x2 * inv_cos(7) * (1.0_wp - x2 * inv_cos(8) &
            * (1.0_wp - x2 * inv_cos(9) * (1.0_wp - x2 * inv_cos(10))))))))))
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

end module model_extremes_bounds
