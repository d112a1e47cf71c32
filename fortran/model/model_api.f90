!> f2py entry of the general model: one call evaluates a whole batch.
module model_api
  use contactsep_kinds, only: wp
  use model_batch, only: design_result, batch_memory, mode_tables, &
      evaluate_design, finish_chunk
  use model_extremes, only: extremes_workspace
  use model_status, only: status_ok
  use model_beam_modes, only: eigenvalue, sigma_parts, mode_value
  use model_given, only: evaluate_given_design
  implicit none
  private
  public :: evaluate_batch, evaluate_batch_given, mode_values

contains

  !> Evaluate m designs (columns of real_in, ints_in; options shared).
  subroutine evaluate_batch(m, n_max, real_in, ints_in, options, t1, &
      v_impact, psi, v0, r, y3_max, t_max, y3_min, t_min, at_end, &
      max_tied, min_tied, status, m1, m2, m3, p1, p2, p3, c3)
    !> Number of designs, and the largest mode count of any member.
    integer, intent(in) :: m, n_max
    !> Designs, one per column (see model_batch), and integer columns.
    real(wp), intent(in) :: real_in(23, m)
    integer, intent(in) :: ints_in(6, m)
    !> Option codes (impact_velocity, lower_response, lc_reading, release).
    integer, intent(in) :: options(4)
    real(wp), intent(out) :: t1(m), v_impact(m), psi(m), v0(m), r(m)
    real(wp), intent(out) :: y3_max(m), t_max(m), y3_min(m), t_min(m)
    real(wp), intent(out) :: m1(m), m2(m), m3(m)
    !> 1 where the maximum sits at the end of the window.
    integer, intent(out) :: at_end(m)
    !> 1 where a later point ties with the maximum (minimum) within 1e-12.
    integer, intent(out) :: max_tied(m), min_tied(m)
    !> Per-design status code (model_status).
    integer, intent(out) :: status(m)
    !> Frequencies and lower-contact coefficients, NaN past a member's N.
    real(wp), intent(out) :: p1(n_max, m), p2(n_max, m), p3(n_max, m)
    real(wp), intent(out) :: c3(n_max, m)
    real(wp) :: kl(n_max, 4), sigma(n_max, 4), g(n_max, 4)
    ! designs are evaluated up to y3's coefficients a chunk at a time, then
    ! the chunk's extremes are searched together (model_extremes)
    integer, parameter :: chunk = 1024
    type(design_result) :: res(chunk)
    real(wp) :: tau(chunk)
    integer :: n3(chunk), ints(6)
    logical :: search(chunk)
    type(batch_memory) :: memory
    type(extremes_workspace) :: ws
    integer :: first, last, i, k

    call mode_tables(n_max, kl, sigma, g)
    do first = 1, m, chunk
      last = min(first + chunk - 1, m)
      do i = first, last
        k = i - first + 1
        ints = ints_in(:, i)
        ! a mode count past the output room is refused, not written past
        if (any(ints(4:6) > n_max)) ints(4:6) = 0
        call evaluate_design(real_in(:, i), ints, options, kl, sigma, g, &
            memory, res(k), p1(:, i), p2(:, i), p3(:, i), c3(:, i))
        search(k) = res(k)%status == status_ok
        n3(k) = ints(6)
        tau(k) = real_in(22, i)
      end do
      call finish_chunk(first, last, res, search, n3, tau, ws, t1, &
          v_impact, psi, v0, r, y3_max, t_max, y3_min, t_min, at_end, &
          max_tied, min_tied, status, m1, m2, m3, p1, p2, p3, c3)
    end do
  end subroutine evaluate_batch

  !> evaluate_batch for designs whose modes are given (model_given: a
  !> Timoshenko beam, elastic supports, point masses); same outputs.
  subroutine evaluate_batch_given(m, n_max, real_in, ints_in, options, &
      b_in, values_in, flex_in, t1, v_impact, psi, v0, r, y3_max, t_max, &
      y3_min, t_min, at_end, max_tied, min_tied, status, m1, m2, m3, p1, &
      p2, p3, c3)
    integer, intent(in) :: m, n_max
    real(wp), intent(in) :: real_in(23, m)
    integer, intent(in) :: ints_in(6, m)
    integer, intent(in) :: options(4)
    !> b_j of members 1..3; X1j(x1), X2j(x2), X3j(x3), X1j(load point);
    !> the upper contact's static flexibility G(a) (model_given).
    real(wp), intent(in) :: b_in(n_max, 3, m), values_in(n_max, 4, m)
    real(wp), intent(in) :: flex_in(m)
    real(wp), intent(out) :: t1(m), v_impact(m), psi(m), v0(m), r(m)
    real(wp), intent(out) :: y3_max(m), t_max(m), y3_min(m), t_min(m)
    real(wp), intent(out) :: m1(m), m2(m), m3(m)
    integer, intent(out) :: at_end(m), max_tied(m), min_tied(m)
    integer, intent(out) :: status(m)
    real(wp), intent(out) :: p1(n_max, m), p2(n_max, m), p3(n_max, m)
    real(wp), intent(out) :: c3(n_max, m)
    integer, parameter :: chunk = 1024
    type(design_result) :: res(chunk)
    real(wp) :: tau(chunk)
    integer :: n3(chunk), ints(6)
    logical :: search(chunk)
    type(extremes_workspace) :: ws
    integer :: first, last, i, k

    do first = 1, m, chunk
      last = min(first + chunk - 1, m)
      do i = first, last
        k = i - first + 1
        ints = ints_in(:, i)
        if (any(ints(4:6) > n_max)) ints(4:6) = 0
        call evaluate_given_design(real_in(:, i), ints, options, &
            b_in(:, :, i), values_in(:, :, i), flex_in(i), res(k), &
            p1(:, i), p2(:, i), p3(:, i), c3(:, i))
        search(k) = res(k)%status == status_ok
        n3(k) = ints(6)
        tau(k) = real_in(22, i)
      end do
      call finish_chunk(first, last, res, search, n3, tau, ws, t1, &
          v_impact, psi, v0, r, y3_max, t_max, y3_min, t_min, at_end, &
          max_tied, min_tied, status, m1, m2, m3, p1, p2, p3, c3)
    end do
  end subroutine evaluate_batch_given

  !> X_j(xi) of end condition `end` for j = 1..n at points xi (for tests).
  subroutine mode_values(end, n, k, xi, kl, values)
    integer, intent(in) :: end, n, k
    real(wp), intent(in) :: xi(k)
    !> k_jL and X_j(xi(i)).
    real(wp), intent(out) :: kl(n), values(n, k)
    real(wp) :: sigma, g
    integer :: i, j

    do j = 1, n
      kl(j) = eigenvalue(end, j)
      call sigma_parts(end, kl(j), sigma, g)
      do i = 1, k
        values(j, i) = mode_value(end, kl(j), sigma, g, xi(i))
      end do
    end do
  end subroutine mode_values

end module model_api
