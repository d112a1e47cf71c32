!> Extremes of the lower-contact response y3(t) = sum c_j sin p_j t over
!> 0 <= t <= tau: the true extremum, not a grid value.
!>
!> Level search: a level samples its window at up to max_level_points
!> points with the modes it resolves (8 samples per period), polishes the
!> best sample, and bounds the unresolved modes by R = sum |c_j|; the
!> extremum lies where the resolved sum is within 2R (plus the grid's own
!> error) of its best, which is the next, narrower window.  When every
!> mode is resolved the polished point is the extremum.  The grid is
!> evaluated with Chebyshev recurrences (no trigonometric call per sample).
module model_extremes
  use contactsep_kinds, only: wp
  use model_responses, only: lower_displacement
  implicit none
  private
  public :: extremes

  integer, parameter :: samples_per_period = 8
  integer, parameter :: max_level_points = 1024
  integer, parameter :: max_levels = 12
  integer, parameter :: polish_iterations = 60
  real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp

contains

  !> Largest and smallest y3 over [0, tau], their times, and whether the
  !> largest sits at t = tau.
  pure subroutine extremes(c, p, tau, y_max, t_max, y_min, t_min, at_end)
    !> Coefficients c_j (in) and frequencies p_j (rad/s) of the live modes.
    real(wp), intent(in) :: c(:), p(:)
    !> Window length (s).
    real(wp), intent(in) :: tau
    real(wp), intent(out) :: y_max, t_max, y_min, t_min
    logical, intent(out) :: at_end
    real(wp) :: first_values(max_level_points), y_tau
    logical :: unused
    integer :: count

    call sample(c, p, 0.0_wp, tau, first_values, count)
    y_tau = lower_displacement(c, p, tau)
    call extreme(c, p, tau, 1.0_wp, first_values(1:count), y_tau, t_max, &
        y_max, at_end)
    call extreme(c, p, tau, -1.0_wp, first_values(1:count), y_tau, t_min, &
        y_min, unused)
    y_min = -y_min
  end subroutine extremes

  !> Number of samples of a window of the given width, and y3 of the
  !> modes they resolve at those samples (Chebyshev recurrences).
  pure subroutine sample(c, p, lo, hi, values, count)
    real(wp), intent(in) :: c(:), p(:), lo, hi
    real(wp), intent(out) :: values(:)
    integer, intent(out) :: count
    real(wp) :: cr(size(c)), s(size(c)), previous(size(c)), two_c(size(c))
    real(wp) :: next_s, acc, width, wanted, h
    integer :: kk, j

    width = hi - lo
    wanted = ceiling(width * samples_per_period * maxval(p) &
        / (2.0_wp * pi))
    count = int(min(real(max_level_points, wp), max(2.0_wp, &
        wanted + 1.0_wp)))
    h = width / (count - 1)
    cr = merge(c, 0.0_wp, p * (4.0_wp * h) <= pi)
    ! Chebyshev recurrence sin(x + h) = 2 cos(h) sin(x) - sin(x - h):
    ! one multiply-add per mode and sample; its rounding grows like
    ! k eps / sin(p h), below 1e-11 here, and only picks the candidate
    ! (the extremum itself is polished with sin and cos).
    s = sin(p * lo)
    previous = sin(p * (lo - h))
    two_c = 2.0_wp * cos(p * h)
    do kk = 1, count
      acc = 0.0_wp
      do j = 1, size(c)
        acc = acc + cr(j) * s(j)
        next_s = two_c(j) * s(j) - previous(j)
        previous(j) = s(j)
        s(j) = next_s
      end do
      values(kk) = acc
    end do
  end subroutine sample

  !> Maximum of sgn*y3 over [0, tau] and its time; first_values are the
  !> first level's samples of y3 (shared by the maximum and minimum).
  pure subroutine extreme(c, p, tau, sgn, first_values, y_tau, t_out, &
      y_out, at_end)
    !> y_tau: y3 at t = tau.
    real(wp), intent(in) :: c(:), p(:), tau, sgn, first_values(:), y_tau
    real(wp), intent(out) :: t_out, y_out
    logical, intent(out) :: at_end
    real(wp) :: values(max_level_points), cr(size(c))
    real(wp) :: lo, hi, width, h, best_t, t_star, t_grid, s_star
    real(wp) :: s_grid, s_best, t_best, rest, grid_error, threshold, y_end
    real(wp) :: left, right, new_lo, new_hi
    logical :: resolved(size(c)), interior
    integer :: level, count, k, kk, first, last

    lo = 0.0_wp
    hi = tau
    best_t = 0.0_wp
    do level = 1, max_levels
      width = hi - lo
      if (level == 1) then
        count = size(first_values)
        values(1:count) = sgn * first_values
      else
        call sample(c, p, lo, hi, values, count)
        values(1:count) = sgn * values(1:count)
      end if
      h = width / (count - 1)
      resolved = p * (4.0_wp * h) <= pi
      cr = merge(c, 0.0_wp, resolved)
      k = maxloc(values(1:count), 1)
      left = grid_point(lo, width, max(k - 1, 1), count)
      right = grid_point(lo, width, min(k + 1, count), count)
      t_grid = grid_point(lo, width, k, count)
      call polish(cr, p, left, right, t_grid, sgn, t_star, interior)
      s_star = sgn * lower_displacement(cr, p, t_star)
      s_grid = values(k)
      if (interior .and. s_star >= s_grid) then
        t_best = t_star
        s_best = s_star
      else
        t_best = t_grid
        s_best = s_grid
      end if
      rest = sum(abs(c), mask=.not. resolved)
      best_t = t_best
      if (rest == 0.0_wp .or. .not. (width > 0.0_wp)) exit
      grid_error = sum(abs(cr) * p**2) * h * h / 8.0_wp
      threshold = s_best - 2.0_wp * rest - grid_error
      first = count
      last = 1
      do kk = 1, count
        if (values(kk) >= threshold) then
          first = min(first, kk)
          last = max(last, kk)
        end if
      end do
      new_lo = grid_point(lo, width, max(first - 1, 1), count)
      new_hi = grid_point(lo, width, min(last + 1, count), count)
      lo = new_lo
      hi = new_hi
    end do
    t_out = best_t
    y_out = sgn * lower_displacement(c, p, t_out)
    ! y3(0) = 0: every term is c_j sin 0
    y_end = 0.0_wp
    if (y_end > y_out) then
      t_out = 0.0_wp
      y_out = y_end
    end if
    y_end = sgn * y_tau
    if (y_end > y_out) then
      t_out = tau
      y_out = y_end
    end if
    at_end = t_out == tau
  end subroutine extreme

  !> Grid point k (1-based) of count points spanning [lo, lo + width].
  pure function grid_point(lo, width, k, count) result(t)
    real(wp), intent(in) :: lo, width
    integer, intent(in) :: k, count
    real(wp) :: t

    t = lo + width * (real(k - 1, wp) / real(count - 1, wp))
  end function grid_point

  !> Critical point of sgn*y3 in [lo, hi] from start (the best sample):
  !> Newton on y3' safeguarded by bisection; interior when y3' changes
  !> sign from + to - there.
  pure subroutine polish(c, p, lo, hi, start, sgn, t, interior)
    real(wp), intent(in) :: c(:), p(:), lo, hi, start, sgn
    real(wp), intent(out) :: t
    logical, intent(out) :: interior
    real(wp) :: a, b, d, dd, newton, t_new
    integer :: iteration, j

    interior = slope(lo) > 0.0_wp .and. slope(hi) < 0.0_wp
    a = lo
    b = hi
    t = start
    do iteration = 1, polish_iterations
      d = 0.0_wp
      dd = 0.0_wp
      do j = 1, size(c)
        d = d + c(j) * p(j) * cos(p(j) * t)
        dd = dd - c(j) * p(j)**2 * sin(p(j) * t)
      end do
      d = sgn * d
      dd = sgn * dd
      if (d > 0.0_wp) then
        a = t
      else
        b = t
      end if
      newton = t - d / dd
      if (newton >= a .and. newton <= b .and. abs(newton) <= huge(1.0_wp)) &
          then
        t_new = newton
      else
        t_new = 0.5_wp * (a + b)
      end if
      if (abs(t_new - t) <= 4.0_wp * epsilon(t) * abs(t)) then
        t = t_new
        exit
      end if
      t = t_new
    end do

  contains

    pure function slope(x) result(d)
      real(wp), intent(in) :: x
      real(wp) :: d

      d = sgn * sum(c * p * cos(p * x))
    end function slope

  end subroutine polish

end module model_extremes
