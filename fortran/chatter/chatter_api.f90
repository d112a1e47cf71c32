!> f2py entry of the contact dynamics: one call runs one simulation.
module chatter_api
  use contactsep_kinds, only: wp
  use chatter_moreau_jean, only: moreau_jean
  use chatter_hertz, only: hertz
  use chatter_contact_law, only: contact_law, law_setup
  use chatter_adaptive, only: adaptive, law_hertz, law_newton
  use chatter_event_driven, only: rigid_stop, jacobi_eigen
  use chatter_status, only: status_ok, status_no_eigenbasis
  use chatter_stop, only: stop_requested
  implicit none
  private
  public :: run_moreau_jean, run_hertz, run_hertz_adaptive
  public :: run_hertz_book, run_hertz_adaptive_book
  public :: run_newton_adaptive, run_rigid_stop
  public :: symmetric_eigen, request_stop, clear_stop

  ! The steppers' entries release the GIL (f2py threadsafe) so that
  ! Python's main thread can wait for them and, on Ctrl-C or SIGTERM,
  ! call request_stop (contactsep/chatter/runners.py).

contains

  !> Ask every running stepper to stop (status_interrupted) within
  !> chatter_stop's stop_check_every steps.
  subroutine request_stop()
    stop_requested = 1
  end subroutine request_stop

  !> Let steppers run again (before a new run).
  subroutine clear_stop()
    stop_requested = 0
  end subroutine clear_stop

  !> Moreau-Jean (see chatter_moreau_jean); q, v are copied, not changed.
  !> crossings(:, i) = time, +c / -c (contact c opens / closes);
  !> gap_max(:, c) = largest gap c, its time; status: chatter_status.
  subroutine run_moreau_jean(n, k, m, p, h, g0, q0, v0, e, dt, theta, &
      steps, stride, samples, threshold, max_cross, t_out, g_out, e_out, &
      p_out, first, crossings, n_cross, gap_max, status, energy_bound)
    !f2py threadsafe
    !f2py real(wp), optional, intent(in) :: energy_bound = 1.0e300
    integer, intent(in) :: n, k, steps, stride, samples, max_cross
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k), q0(n), v0(n)
    real(wp), intent(in) :: e, dt, theta, threshold, energy_bound
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), p_out(k, samples)
    !> First episode of contact 1: time, impulse (-1: none).
    real(wp), intent(out) :: first(2)
    real(wp), intent(out) :: crossings(2, max_cross), gap_max(2, k)
    integer, intent(out) :: n_cross, status
    real(wp) :: q(n), v(n)

    q = q0
    v = v0
    call moreau_jean(n, k, m, p, h, g0, q, v, e, dt, theta, steps, &
        stride, samples, threshold, max_cross, t_out, g_out, e_out, &
        p_out, first, crossings, n_cross, gap_max, energy_bound, status)
  end subroutine run_moreau_jean

  !> Hertz splitting (see chatter_hertz); q, v are copied, not changed.
  !> status: chatter_status (ok, energy_bound, interrupted).
  !> cmat: the static correction's series flexibilities (in/lb; 0: the
  !> plain truncation).
  subroutine run_hertz(n, k, m, p, h, g0, cmat, q0, v0, stiffness, chi, &
      dt, steps, stride, samples, t_out, g_out, e_out, p_out, first, &
      status, energy_bound)
    !f2py threadsafe
    !f2py real(wp), optional, intent(in) :: energy_bound = 1.0e300
    integer, intent(in) :: n, k, steps, stride, samples
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k), q0(n), v0(n)
    real(wp), intent(in) :: cmat(k, k)
    real(wp), intent(in) :: stiffness, chi, dt, energy_bound
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), p_out(k, samples)
    !> First episode of contact 1: time, impulse (-1: none).
    real(wp), intent(out) :: first(2)
    integer, intent(out) :: status
    real(wp) :: q(n), v(n), book(2)
    type(contact_law) :: law

    q = q0
    v = v0
    call law_setup(law, stiffness, chi, 0.0_wp, 0.0_wp, 0.0_wp)
    call hertz(n, k, m, p, h, g0, cmat, q, v, law, dt, steps, &
        stride, samples, t_out, g_out, e_out, p_out, first, energy_bound, &
        status, book)
  end subroutine run_hertz

  !> run_hertz with every law of the Hertz family (chatter_contact_law:
  !> yield pressure p_y > 0 is Thornton's, with E* (psi) and the button
  !> radius R (in)) and the energy book: the final state q_end, v_end,
  !> and book = dissipated energy, the contacts' stored energy (in lb).
  subroutine run_hertz_book(n, k, m, p, h, g0, cmat, q0, v0, stiffness, &
      chi, pressure, e_star, radius, line, dt, steps, stride, samples, &
      energy_bound, t_out, g_out, e_out, p_out, first, q_end, v_end, &
      book, status)
    !f2py threadsafe
    integer, intent(in) :: n, k, steps, stride, samples
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k), q0(n), v0(n)
    real(wp), intent(in) :: cmat(k, k)
    real(wp), intent(in) :: stiffness, chi, pressure, e_star, radius
    !> 1: a line contact (cylindrical button, F = k delta), 0: a sphere.
    integer, intent(in) :: line
    real(wp), intent(in) :: dt, energy_bound
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), p_out(k, samples)
    real(wp), intent(out) :: first(2), q_end(n), v_end(n), book(2)
    integer, intent(out) :: status
    type(contact_law) :: law

    q_end = q0
    v_end = v0
    call law_setup(law, stiffness, chi, pressure, e_star, radius, &
        line /= 0)
    call hertz(n, k, m, p, h, g0, cmat, q_end, v_end, law, dt, steps, &
        stride, samples, t_out, g_out, e_out, p_out, first, energy_bound, &
        status, book)
  end subroutine run_hertz_book

  !> Hertz, adaptive (see chatter_adaptive); q0, v0 are copied.
  !> crossings(:, i) = time, +c / -c (contact c opens / closes);
  !> gap_max(:, c) = largest gap c, its time; counts = flight steps,
  !> fixed steps, flow evaluations; status: chatter_status; cmat as
  !> run_hertz's.
  subroutine run_hertz_adaptive(n, k, m, p, h, g0, cmat, q0, v0, &
      stiffness, chi, dt, steps, stride, samples, threshold, n_moving, &
      energy_bound, max_cross, t_out, g_out, e_out, first, crossings, &
      n_cross, gap_max, counts, status)
    !f2py threadsafe
    integer, intent(in) :: n, k, steps, stride, samples, n_moving
    integer, intent(in) :: max_cross
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k), q0(n), v0(n)
    real(wp), intent(in) :: cmat(k, k)
    real(wp), intent(in) :: stiffness, chi, dt, threshold, energy_bound
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), first(2)
    real(wp), intent(out) :: crossings(2, max_cross), gap_max(2, k)
    integer, intent(out) :: n_cross, counts(3), status
    real(wp) :: q(n), v(n)

    q = q0
    v = v0
    call adaptive(law_hertz, n, k, m, p, h, g0, cmat, q, v, stiffness, &
        chi, 0.0_wp, dt, steps, stride, samples, threshold, n_moving, &
        energy_bound, max_cross, t_out, g_out, e_out, first, crossings, &
        n_cross, gap_max, counts, status)
  end subroutine run_hertz_adaptive

  !> run_hertz_adaptive with every law of the Hertz family and the
  !> energy book (as run_hertz_book).  stop_open >= 0 stops the run at
  !> its first discontinuity event (chatter_adaptive_event).
  subroutine run_hertz_adaptive_book(n, k, m, p, h, g0, cmat, q0, v0, &
      stiffness, chi, pressure, e_star, radius, line, dt, steps, stride, &
      samples, threshold, n_moving, energy_bound, max_cross, t_out, &
      g_out, e_out, first, crossings, n_cross, gap_max, counts, q_end, &
      v_end, book, status, stop_open)
    !f2py threadsafe
    !f2py real(wp), optional, intent(in) :: stop_open = -1.0
    integer, intent(in) :: n, k, steps, stride, samples, n_moving
    integer, intent(in) :: max_cross
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k), q0(n), v0(n)
    real(wp), intent(in) :: cmat(k, k)
    real(wp), intent(in) :: stiffness, chi, pressure, e_star, radius
    !> 1: a line contact (cylindrical button, F = k delta), 0: a sphere.
    integer, intent(in) :: line
    real(wp), intent(in) :: dt, threshold, energy_bound
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), first(2)
    real(wp), intent(out) :: crossings(2, max_cross), gap_max(2, k)
    integer, intent(out) :: n_cross, counts(3), status
    real(wp), intent(out) :: q_end(n), v_end(n), book(2)
    real(wp), intent(in) :: stop_open
    type(contact_law) :: law

    q_end = q0
    v_end = v0
    call law_setup(law, stiffness, chi, pressure, e_star, radius, &
        line /= 0)
    call adaptive(law_hertz, n, k, m, p, h, g0, cmat, q_end, v_end, &
        stiffness, chi, 0.0_wp, dt, steps, stride, samples, threshold, &
        n_moving, energy_bound, max_cross, t_out, g_out, e_out, first, &
        crossings, n_cross, gap_max, counts, status, law, book, &
        stop_open)
  end subroutine run_hertz_adaptive_book

  !> Newton's law, adaptive (see chatter_adaptive): arguments and
  !> results as run_hertz_adaptive, with the restitution e instead of
  !> the Hertz constants, and the final state q_end, v_end;
  !> stop_open as run_hertz_adaptive_book's.
  subroutine run_newton_adaptive(n, k, m, p, h, g0, q0, v0, e, dt, &
      steps, stride, samples, threshold, n_moving, energy_bound, &
      max_cross, t_out, g_out, e_out, first, crossings, n_cross, &
      gap_max, counts, q_end, v_end, status, stop_open)
    !f2py threadsafe
    !f2py real(wp), optional, intent(in) :: stop_open = -1.0
    integer, intent(in) :: n, k, steps, stride, samples, n_moving
    integer, intent(in) :: max_cross
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k), q0(n), v0(n)
    real(wp), intent(in) :: e, dt, threshold, energy_bound
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), first(2)
    real(wp), intent(out) :: crossings(2, max_cross), gap_max(2, k)
    integer, intent(out) :: n_cross, counts(3), status
    real(wp), intent(out) :: q_end(n), v_end(n)
    real(wp), intent(in) :: stop_open
    real(wp) :: no_series(k, k)

    q_end = q0
    v_end = v0
    ! Newton's rigid law takes no series compliance
    no_series = 0.0_wp
    call adaptive(law_newton, n, k, m, p, h, g0, no_series, q_end, v_end, &
        0.0_wp, 0.0_wp, &
        e, dt, steps, stride, samples, threshold, n_moving, &
        energy_bound, max_cross, t_out, g_out, e_out, first, crossings, &
        n_cross, gap_max, counts, status, stop_open=stop_open)
  end subroutine run_newton_adaptive

  !> Appendix E on a rigid stop (see chatter_event_driven's rigid_stop);
  !> q0, v0 are copied, not changed.  impacts(:, i) = time, impulse,
  !> contact velocity before and after, energy after; closure(i) = 0
  !> flight, 1 a rest began, 2 closed and left at once; rests(:, k) =
  !> start, end; energies = initial, final; status: chatter_status.
  subroutine run_rigid_stop(n, p, x, mass, q0, v0, e, t_end, zeno_speed, &
      max_impacts, max_rests, impacts, n_impacts, closure, rests, &
      n_rests, q_end, v_end, energies, status)
    integer, intent(in) :: n, max_impacts, max_rests
    real(wp), intent(in) :: p(n), x(n), mass, q0(n), v0(n)
    real(wp), intent(in) :: e, t_end, zeno_speed
    real(wp), intent(out) :: impacts(5, max_impacts)
    integer, intent(out) :: n_impacts, closure(max_impacts)
    real(wp), intent(out) :: rests(2, max_rests)
    integer, intent(out) :: n_rests
    real(wp), intent(out) :: q_end(n), v_end(n), energies(2)
    integer, intent(out) :: status

    q_end = q0
    v_end = v0
    call rigid_stop(n, p, x, mass, q_end, v_end, e, t_end, zeno_speed, &
        max_impacts, max_rests, impacts, n_impacts, closure, rests, &
        n_rests, energies, status)
  end subroutine run_rigid_stop

  !> Symmetric eigen-decomposition by cyclic Jacobi (ascending w,
  !> a = v diag(w) v^T); status ok or no_eigenbasis (chatter_status).
  subroutine symmetric_eigen(n, a, w, v, status)
    integer, intent(in) :: n
    real(wp), intent(in) :: a(n, n)
    real(wp), intent(out) :: w(n), v(n, n)
    integer, intent(out) :: status
    logical :: ok

    call jacobi_eigen(n, a, w, v, ok)
    status = merge(status_ok, status_no_eigenbasis, ok)
  end subroutine symmetric_eigen

end module chatter_api
