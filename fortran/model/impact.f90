!> The upper contact's release and first impact (Chapter III, App. A).
module model_impact
  use contactsep_kinds, only: wp
  implicit none
  private
  public :: release_amplitudes, upper_displacement, upper_velocity, &
      first_impact, impact_velocity

contains

  !> A_j = y_s X_j(a) / ((k_jL)^4 G(a)): exact modal coefficients of the
  !> static shape under a point load at a with y(a) = y_s (A-(7)).
  pure subroutine release_amplitudes(ys, load_values, kl, flexibility, amp)
    real(wp), intent(in) :: ys, load_values(:), kl(:), flexibility
    !> A_j, one per mode.
    real(wp), intent(out) :: amp(:)

    amp = ys * load_values / (kl**4 * flexibility)
  end subroutine release_amplitudes

  !> y1(x1, t) = sum A_j X_j(x1) cos p_j t (III-(3)); coef = A_j X_j(x1).
  pure function upper_displacement(coef, p, t) result(y)
    real(wp), intent(in) :: coef(:), p(:), t
    real(wp) :: y

    y = sum(coef * cos(p * t))
  end function upper_displacement

  !> dy1/dt(x1, t) = -sum p_j A_j X_j(x1) sin p_j t (III-(4)).
  pure function upper_velocity(coef, p, t) result(v)
    real(wp), intent(in) :: coef(:), p(:), t
    real(wp) :: v

    v = -sum(coef * p * sin(p * t))
  end function upper_velocity

  !> First t > 0 with y1(x1, t) = gap; missed when none before horizon.
  !>
  !> Safe steps: B = sum |A_j X_j| p_j^2 bounds |y1''|, so stepping to
  !> the first root of f + f' s - B s^2/2 (f = y1 - gap) never passes the
  !> first crossing; near a simple root the steps converge quadratically.
  !> A last Newton step from the left polishes t1.
  pure subroutine first_impact(coef, p, gap, horizon, t1, missed)
    real(wp), intent(in) :: coef(:), p(:), gap, horizon
    real(wp), intent(out) :: t1
    logical, intent(out) :: missed
    real(wp) :: bound, t, f, d, root, step
    integer :: iteration

    bound = sum(abs(coef) * p**2)
    t = 0.0_wp
    f = upper_displacement(coef, p, t) - gap
    missed = .not. (f > 0.0_wp) .or. .not. (bound > 0.0_wp)
    if (missed) then
      t1 = 0.0_wp
      return
    end if
    do iteration = 1, 100000
      call upper_state(coef, p, t, f, d)
      f = f - gap
      root = sqrt(d * d + 2.0_wp * bound * max(f, 0.0_wp))
      if (d >= 0.0_wp) then
        step = (d + root) / bound
      else
        step = 2.0_wp * max(f, 0.0_wp) / (root - d)
      end if
      if (f <= 0.0_wp .or. step <= 1.0e-13_wp * max(t, 1.0e-3_wp)) exit
      t = t + step
      if (t > horizon) then
        missed = .true.
        t1 = 0.0_wp
        return
      end if
    end do
    call upper_state(coef, p, t, f, d)
    f = f - gap
    if (d < 0.0_wp) t = t - f / d
    t1 = t
  end subroutine first_impact

  !> y1(x1, t) and dy1/dt(x1, t) together.  The cosines and the sines are
  !> taken in separate array statements, which gfortran vectorises with
  !> glibc's vector sin and cos (libmvec; a scalar sincos per mode took
  !> most of the model's time outside the extremes at N = 32), a chunk of
  !> modes at a time (fixed-size arrays: on the stack, not allocated).
  pure subroutine upper_state(coef, p, t, y, v)
    real(wp), intent(in) :: coef(:), p(:), t
    real(wp), intent(out) :: y, v
    integer, parameter :: chunk = 64
    real(wp) :: phase(chunk), cosines(chunk), sines(chunk)
    integer :: first, last, m

    y = 0.0_wp
    v = 0.0_wp
    do first = 1, size(coef), chunk
      last = min(first + chunk - 1, size(coef))
      m = last - first + 1
      phase(1:m) = p(first:last) * t
      cosines(1:m) = cos(phase(1:m))
      sines(1:m) = sin(phase(1:m))
      y = y + sum(coef(first:last) * cosines(1:m))
      v = v - sum(coef(first:last) * p(first:last) * sines(1:m))
    end do
  end subroutine upper_state

  !> V = |dy1/dt(x1, t1)|; listing: |sum p_j A_j X_j(x1)| (ACT, no sin).
  pure function impact_velocity(coef, p, t1, listing) result(v)
    real(wp), intent(in) :: coef(:), p(:), t1
    logical, intent(in) :: listing
    real(wp) :: v

    if (listing) then
      v = abs(sum(coef * p))
    else
      v = abs(upper_velocity(coef, p, t1))
    end if
  end function impact_velocity

end module model_impact
