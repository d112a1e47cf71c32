!> Appendix E, compiled: one beam's contact point against a rigid stop,
!> event-driven with the exact modal flow between events.
!> Twin: contactsep/chatter/event_driven.py (simulate_rigid_stop); the
!> algorithm, its thresholds and its order of decisions are the twin's.
!>
!> Every segment (free flight or resting contact) is a set of decoupled
!> oscillators: modal coordinate k moves as
!>   a_k cos(w_k tau) + bw_k sin(w_k tau),   bw_k = b_k / w_k,
!> and the watched quantity (contact displacement, contact force) is
!> sum_k c_k times that.  A mode that does not move (w_k = 0: the
!> constrained direction of a resting contact) has a_k = bw_k = 0.
module chatter_event_driven
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use contactsep_kinds, only: wp
  use chatter_status, only: st_ok => status_ok, &
      st_impacts_full => status_impacts_full, &
      st_bad_input => status_bad_input, st_rests_full => status_rests_full, &
      st_no_eigen => status_no_eigenbasis
  implicit none
  private
  public :: rigid_stop, jacobi_eigen, max_steps

  !> Safe steps allowed per search before a grazing approach is taken as
  !> a contact (the twin's MAX_STEPS).
  integer, parameter :: max_steps = 200000
  !> Sweeps allowed to the cyclic Jacobi eigensolver.
  integer, parameter :: max_sweeps = 100
  real(wp), parameter :: two_pi = 6.283185307179586476925286766559_wp
  real(wp), parameter :: tiny_scale = 1.0e-300_wp

contains

  !> Watched quantity f = sum c (a cos + bw sin) and its rate at tau.
  pure subroutine modal_value(n, w, a, bw, c, tau, f, d)
    integer, intent(in) :: n
    real(wp), intent(in) :: w(n), a(n), bw(n), c(n), tau
    real(wp), intent(out) :: f, d
    real(wp) :: cs(n), sn(n)

    cs = cos(w * tau)
    sn = sin(w * tau)
    f = sum(c * (a * cs + bw * sn))
    d = sum(c * w * (bw * cs - a * sn))
  end subroutine modal_value

  !> Modal displacements and velocities of the segment after tau.
  pure subroutine modal_state(n, w, a, bw, tau, qm, vm)
    integer, intent(in) :: n
    real(wp), intent(in) :: w(n), a(n), bw(n), tau
    real(wp), intent(out) :: qm(n), vm(n)
    real(wp) :: cs(n), sn(n)

    cs = cos(w * tau)
    sn = sin(w * tau)
    qm = a * cs + bw * sn
    vm = w * (bw * cs - a * sn)
  end subroutine modal_state

  !> B = sum |c| w^2 amp >= |f''| at every later time of the segment.
  pure function modal_bound(n, w, a, bw, c) result(bound)
    integer, intent(in) :: n
    real(wp), intent(in) :: w(n), a(n), bw(n), c(n)
    real(wp) :: bound

    bound = sum(abs(c) * w**2 * sqrt(a**2 + bw**2))
  end function modal_bound

  !> First tau in (0, horizon] where f(shift + tau) reaches 0 from above,
  !> by safe steps (the twin's _first_root); found is false if none.
  pure subroutine first_root(n, w, a, bw, c, shift, bound, scale, &
      horizon, tau, found)
    integer, intent(in) :: n
    real(wp), intent(in) :: w(n), a(n), bw(n), c(n)
    real(wp), intent(in) :: shift, bound, scale, horizon
    real(wp), intent(out) :: tau
    logical, intent(out) :: found
    real(wp) :: f, d, root, step
    logical :: small
    integer :: i

    tau = 0.0_wp
    found = .true.
    do i = 1, max_steps
      call modal_value(n, w, a, bw, c, shift + tau, f, d)
      if (f <= 0.0_wp) return
      root = sqrt(d * d + 2.0_wp * bound * f)
      if (d >= 0.0_wp) then
        step = (d + root) / bound
      else
        step = 2.0_wp * f / (root - d)
      end if
      small = step <= 1.0e-15_wp * max(tau, 1.0e-9_wp)
      ! converged on a crossing; the Newton step -f/d is taken only where
      ! the safe step agrees with it (f, d both at round-off, as at a
      ! release from rest, would otherwise jump over real contacts)
      if (d < 0.0_wp .and. (small .or. f <= 1.0e-15_wp * scale) .and. &
          -f / d <= 2.0_wp * step) then
        tau = tau - f / d
        return
      end if
      if (small .and. f <= 1.0e-12_wp * scale) return   ! grazing
      tau = tau + step
      if (tau > horizon) then
        found = .false.
        return
      end if
    end do
    ! a grazing approach: taken as the contact
  end subroutine first_root

  !> Cyclic Jacobi: a = v diag(d) v^T for symmetric a; d ascending, v's
  !> columns orthonormal.  ok is false if max_sweeps did not converge.
  pure subroutine jacobi_eigen(n, a, d, v, ok)
    integer, intent(in) :: n
    real(wp), intent(in) :: a(n, n)
    real(wp), intent(out) :: d(n), v(n, n)
    logical, intent(out) :: ok
    real(wp) :: b(n, n), theta, t, cs, sn, off, total, col(n), tmp
    integer :: sweep, i, j, k, low

    b = 0.5_wp * (a + transpose(a))
    v = 0.0_wp
    do i = 1, n
      v(i, i) = 1.0_wp
    end do
    total = sum(b**2)
    ok = .false.
    do sweep = 1, max_sweeps
      off = 0.0_wp
      do j = 2, n
        off = off + sum(b(1:j - 1, j)**2)
      end do
      ! off-diagonal norm at round-off of the matrix: converged
      if (off <= (epsilon(1.0_wp) * 1.0e-2_wp)**2 * total) then
        ok = .true.
        exit
      end if
      do i = 1, n - 1
        do j = i + 1, n
          if (b(i, j) == 0.0_wp) cycle
          theta = (b(j, j) - b(i, i)) / (2.0_wp * b(i, j))
          if (abs(theta) > 1.0e150_wp) then
            t = 0.5_wp / theta
          else
            t = sign(1.0_wp, theta) / (abs(theta) + sqrt(theta**2 + 1))
          end if
          cs = 1.0_wp / sqrt(t**2 + 1.0_wp)
          sn = t * cs
          call rotate(b(:, i), b(:, j), cs, sn)
          call rotate(b(i, :), b(j, :), cs, sn)
          call rotate(v(:, i), v(:, j), cs, sn)
          b(i, j) = 0.0_wp
          b(j, i) = 0.0_wp
        end do
      end do
    end do
    do i = 1, n
      d(i) = b(i, i)
    end do
    ! ascending, as numpy.linalg.eigh
    do i = 1, n - 1
      low = i
      do k = i + 1, n
        if (d(k) < d(low)) low = k
      end do
      if (low /= i) then
        tmp = d(i)
        d(i) = d(low)
        d(low) = tmp
        col = v(:, i)
        v(:, i) = v(:, low)
        v(:, low) = col
      end if
    end do
  end subroutine jacobi_eigen

  !> Plane rotation of the pair (x, y) by cos cs, sin sn.
  pure subroutine rotate(x, y, cs, sn)
    real(wp), intent(inout) :: x(:), y(:)
    real(wp), intent(in) :: cs, sn
    real(wp) :: keep(size(x))

    keep = x
    x = cs * keep - sn * y
    y = sn * keep + cs * y
  end subroutine rotate

  !> Modes of the propped beam: eigenvectors of P K P, P = I - X X^T/sx,
  !> K = diag(p^2); the eigenvector most aligned with X gets omega = 0.
  pure subroutine constrained_basis(n, p, x, sx, vectors, omega, ok)
    integer, intent(in) :: n
    real(wp), intent(in) :: p(n), x(n), sx
    real(wp), intent(out) :: vectors(n, n), omega(n)
    logical, intent(out) :: ok
    real(wp) :: projector(n, n), stiff(n, n)
    integer :: i

    projector = -spread(x, 2, n) * spread(x, 1, n) / sx
    do i = 1, n
      projector(i, i) = projector(i, i) + 1.0_wp
    end do
    stiff = matmul(projector, spread(p**2, 2, n) * projector)
    call jacobi_eigen(n, stiff, omega, vectors, ok)
    omega = sqrt(max(omega, 0.0_wp))
    ! the constrained direction X itself does not move
    omega(maxloc(abs(matmul(x, vectors)), 1)) = 0.0_wp
  end subroutine constrained_basis

  !> 0.5 M sum (v^2 + p^2 q^2).
  pure function energy(n, p, mass, q, v) result(en)
    integer, intent(in) :: n
    real(wp), intent(in) :: p(n), mass, q(n), v(n)
    real(wp) :: en

    en = 0.5_wp * mass * sum(v**2 + (p * q)**2)
  end function energy

  !> True if the arguments make a run (see status_bad_input).
  pure function good_input(n, p, x, mass, q, v, e, t_end, zeno_speed, &
      max_impacts, max_rests) result(good)
    integer, intent(in) :: n, max_impacts, max_rests
    real(wp), intent(in) :: p(n), x(n), mass, q(n), v(n)
    real(wp), intent(in) :: e, t_end, zeno_speed
    logical :: good

    good = .false.
    if (n < 1 .or. max_impacts < 1 .or. max_rests < 1) return
    if (.not. (all(ieee_is_finite(p)) .and. all(ieee_is_finite(x)) &
        .and. all(ieee_is_finite(q)) .and. all(ieee_is_finite(v)))) &
        return
    if (.not. (ieee_is_finite(mass) .and. ieee_is_finite(e) .and. &
        ieee_is_finite(t_end) .and. ieee_is_finite(zeno_speed))) return
    if (any(p <= 0.0_wp) .or. mass <= 0.0_wp .or. sum(x**2) <= 0.0_wp) &
        return
    if (e < 0.0_wp .or. e > 1.0_wp .or. t_end < 0.0_wp) return
    if (zeno_speed < 0.0_wp) return
    good = .true.
  end function good_input

  !> The beam (p_j, X_j at the contact, mass M) from (q, v) against a
  !> rigid stop at y = sum X_j q_j = 0, the beam above it, until t_end.
  !> impacts(:, i) = t, psi, u-, u+, energy after; closure(i) = what the
  !> impact began: 0 flight, 1 the rest rests(:, k) (start, end), 2 a
  !> closed contact left at once (the stop would pull); q, v end as the
  !> state at t_end, or at the last impact if the run stopped early.
  subroutine rigid_stop(n, p, x, mass, q, v, e, t_end, zeno_speed, &
      max_impacts, max_rests, impacts, n_impacts, closure, rests, &
      n_rests, energies, status)
    integer, intent(in) :: n, max_impacts, max_rests
    real(wp), intent(in) :: p(n), x(n), mass, e, t_end, zeno_speed
    !> Initial modal state, overwritten by the final one.
    real(wp), intent(inout) :: q(n), v(n)
    real(wp), intent(out) :: impacts(5, max_impacts)
    integer, intent(out) :: n_impacts, closure(max_impacts)
    real(wp), intent(out) :: rests(2, max_rests)
    integer, intent(out) :: n_rests
    !> Energy at release and at the end (in lb).
    real(wp), intent(out) :: energies(2)
    !> A code of chatter_status (ok, impacts_full, bad_input, rests_full,
    !> no_eigenbasis).
    integer, intent(out) :: status
    real(wp) :: sx, scale, t, tau, start, bound, y0, yd0, pmax
    real(wp) :: u_minus, u_plus, psi, first_speed, f0, fd0, release
    real(wp) :: noise
    real(wp) :: t_stop
    real(wp) :: bw(n), qm(n), vm(n), vectors(n, n), omega(n)
    real(wp) :: ra(n), rbw(n), rc(n)
    logical :: leaving, found, ok, closing
    integer :: events

    impacts = 0.0_wp
    closure = 0
    rests = 0.0_wp
    n_impacts = 0
    n_rests = 0
    energies = 0.0_wp
    if (.not. good_input(n, p, x, mass, q, v, e, t_end, zeno_speed, &
        max_impacts, max_rests)) then
      status = st_bad_input
      return
    end if
    status = st_ok
    sx = sum(x**2)
    scale = max(abs(sum(q * x)), tiny_scale)
    pmax = maxval(p)
    t = 0.0_wp
    energies(1) = energy(n, p, mass, q, v)
    first_speed = 0.0_wp
    leaving = .false.
    events = 0
    do while (t < t_end .and. n_impacts < max_impacts .and. &
        events < 4 * max_impacts)
      events = events + 1
      ! flight from (q, v): the contact displacement is sum x q(tau)
      bw = v / p
      bound = max(modal_bound(n, p, q, bw, x), tiny_scale)
      y0 = sum(q * x)
      yd0 = sum(v * x)
      start = 0.0_wp
      ! approaching beyond the round-off of the modal sum u = sum x v
      closing = yd0 < -64.0_wp * epsilon(1.0_wp) * sum(abs(x * v))
      if (y0 <= 0.0_wp .and. yd0 <= 0.0_wp .and. .not. leaving .and. &
          (n_impacts > 0 .or. closing)) then
        ! still closing (or a start at the stop, to within rounding,
        ! that approaches it): an impact now.  Without the start's case
        ! y0 = -1e-18 flew into the stop for up to 1e-3 of the shortest
        ! period while y0 = +1e-18 met it at once (issue 26)
        tau = 0.0_wp
        found = .true.
      else
        if (leaving .or. y0 <= 0.0_wp) then
          ! at the stop with (almost) no normal velocity: it leaves as
          ! y ~ tau^2 or tau^3; start where it is clear of it by more
          ! than the round-off of the modal sum (else that round-off is
          ! found as a contact with no approach)
          noise = 64.0_wp * epsilon(1.0_wp) &
              * sum(abs(x * q) + abs(x * bw))
          start = 1.0e-12_wp * two_pi / pmax
          do
            call modal_value(n, p, q, bw, x, start, y0, yd0)
            if (y0 > noise .or. start >= 1.0e-3_wp * two_pi / pmax) exit
            start = 2.0_wp * start
          end do
        end if
        call first_root(n, p, q, bw, x, start, bound, scale, &
            t_end - t - start, tau, found)
        if (found) tau = start + tau
      end if
      leaving = .false.
      if (.not. found) then
        call modal_state(n, p, q, bw, t_end - t, qm, vm)
        q = qm
        v = vm
        t = t_end
        exit
      end if
      call modal_state(n, p, q, bw, tau, qm, vm)
      q = qm
      v = vm
      t = t + tau
      u_minus = sum(v * x)
      if (u_minus >= 0.0_wp) then
        ! at the stop but not approaching it (leaving a rest, or the
        ! modal sum's round-off near y = 0): no impact; fly on
        leaving = .true.
        cycle
      end if
      psi = -(1.0_wp + e) * mass * u_minus / sx
      v = v + x * psi / mass
      u_plus = sum(v * x)
      if (first_speed == 0.0_wp) first_speed = abs(u_minus)
      n_impacts = n_impacts + 1
      impacts(:, n_impacts) = [t, psi, u_minus, u_plus, &
          energy(n, p, mass, q, v)]
      if (u_plus >= zeno_speed * first_speed) cycle
      ! accumulation: close the contact and move constrained
      if (n_rests == max_rests) then
        status = st_rests_full
        exit
      end if
      v = v - x * sum(v * x) / sx
      call constrained_basis(n, p, x, sx, vectors, omega, ok)
      if (.not. ok) then
        status = st_no_eigen
        exit
      end if
      q = q - x * sum(q * x) / sx
      ! contact force = M sum X_j p_j^2 q_j / sum X^2, in the basis
      call rest_segment(n, omega, vectors, q, v, &
          matmul(x * p**2, vectors) * (mass / sx), ra, rbw, rc)
      call modal_value(n, omega, ra, rbw, rc, 0.0_wp, f0, fd0)
      if (f0 <= 0.0_wp) then
        ! the stop pulls: the contact opens at once, no rest
        closure(n_impacts) = 2
        leaving = .true.
        cycle
      end if
      closure(n_impacts) = 1
      call first_root(n, omega, ra, rbw, rc, 0.0_wp, &
          max(modal_bound(n, omega, ra, rbw, rc), tiny_scale), &
          max(abs(f0), tiny_scale), t_end - t, release, found)
      t_stop = t_end
      if (found) t_stop = t + release
      n_rests = n_rests + 1
      rests(:, n_rests) = [t, t_stop]
      call modal_state(n, omega, ra, rbw, t_stop - t, qm, vm)
      q = matmul(vectors, qm)
      v = matmul(vectors, vm)
      t = t_stop
      if (.not. found) exit
      leaving = .true.
    end do
    if (status == st_ok .and. t < t_end) status = st_impacts_full
    energies(2) = energy(n, p, mass, q, v)
  end subroutine rigid_stop

  !> Coordinates of a resting segment from (q, v) in the constrained
  !> basis; the watched weights c (already in the basis) are kept for the
  !> moving modes only.
  pure subroutine rest_segment(n, omega, vectors, q, v, cw, a, bw, c)
    integer, intent(in) :: n
    real(wp), intent(in) :: omega(n), vectors(n, n), q(n), v(n), cw(n)
    real(wp), intent(out) :: a(n), bw(n), c(n)
    integer :: k

    a = matmul(q, vectors)
    bw = matmul(v, vectors)
    c = cw
    do k = 1, n
      if (omega(k) > 0.0_wp) then
        bw(k) = bw(k) / omega(k)
      else
        a(k) = 0.0_wp
        bw(k) = 0.0_wp
        c(k) = 0.0_wp
      end if
    end do
  end subroutine rest_segment

end module chatter_event_driven
