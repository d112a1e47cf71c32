!> The general model (eq. 23) on a batch of designs, one status each.
!>
!> Columns of a design row (CONTRACT with contactsep.model.design.pack):
!> L1 b1 h1 gamma1 E1 x1 | L2 b2 h2 gamma2 E2 x2 Lc | L3 b3 h3 gamma3 E3 x3
!> | ys e tau gap; integer row: end1 end2 end3 n1 n2 n3; options:
!> impact_velocity (0 exact, 1 listing), lower_response (0 as printed,
!> 1 impulse), lc_reading (0 listing, 1 frequencies, 2 mass), release
!> (0 tip, 1 contact).
module model_batch
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, &
      ieee_is_finite
  use contactsep_kinds, only: wp
  use model_extremes, only: extremes, extremes_workspace
  use model_status, only: status_ok, status_no_impact, &
      status_invalid_input, status_not_finite, status_unresolved
  use model_beam_modes, only: eigenvalue, sigma_parts, mode_value, &
      static_flexibility, clamped_free
  use model_members, only: member_constants, frequency
  use model_impact, only: release_amplitudes, first_impact, impact_velocity
  use model_responses, only: impulse, separator_velocity, &
      lower_coefficients, mass_ratio
  implicit none
  private
  public :: mode_tables, evaluate_design, finish_design, design_is_valid, &
      clear, finish_chunk

  !> Number of real columns of a design row.
  integer, parameter, public :: n_real = 23
  real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp

  !> Per-design results (one row of the batch outputs).
  type, public :: design_result
    real(wp) :: t1, v_impact, psi, v0, r, y3_max, t_max, y3_min, t_min
    real(wp) :: m1, m2, m3
    logical :: at_end = .false., max_tied = .false., min_tied = .false.
    integer :: status = status_ok
  end type design_result

  !> What the previous design of a batch computed that the next may share:
  !> the mode values at each contact point and the upper contact's impact.
  !> A sweep often varies one member; reusing the others' work changes
  !> no bit of a result (the same inputs give the same values).
  type, public :: batch_memory
    !> (end, n) and xi of the last mode values at points 1..4 (x1, x2, x3
    !> and the load point), and the values.
    integer :: point_key(2, 4) = 0
    real(wp) :: point_xi(4) = -1.0_wp
    real(wp), allocatable :: point_values(:, :)
    !> Inputs that fix the upper contact's impact, and its t1 and V.
    real(wp) :: upper_key(8) = -1.0_wp
    integer :: upper_ints(4) = -1
    real(wp) :: t1 = 0.0_wp, v_impact = 0.0_wp
    logical :: missed = .true.
  end type batch_memory

contains

  !> k_jL, sigma_j and g_j of the four end conditions, j = 1..n_max.
  pure subroutine mode_tables(n_max, kl, sigma, g)
    integer, intent(in) :: n_max
    real(wp), intent(out) :: kl(n_max, 4), sigma(n_max, 4), g(n_max, 4)
    integer :: end, j

    do end = 1, 4
      do j = 1, n_max
        kl(j, end) = eigenvalue(end, j)
        call sigma_parts(end, kl(j, end), sigma(j, end), g(j, end))
      end do
    end do
  end subroutine mode_tables

  !> True when every value of a design is in range.
  pure function design_is_valid(row, ints) result(ok)
    real(wp), intent(in) :: row(n_real)
    integer, intent(in) :: ints(6)
    logical :: ok
    integer, parameter :: positive(16) = [1, 2, 3, 4, 5, 7, 8, 9, 10, &
        11, 14, 15, 16, 17, 18, 22]

    ok = all(ieee_is_finite(row)) .and. all(row(positive) > 0.0_wp)
    ok = ok .and. row(6) > 0.0_wp .and. row(6) <= row(1)
    ok = ok .and. row(12) > 0.0_wp .and. row(12) <= row(7)
    ok = ok .and. row(19) > 0.0_wp .and. row(19) <= row(14)
    ok = ok .and. row(13) >= 0.0_wp
    ok = ok .and. row(21) >= 0.0_wp .and. row(21) <= 1.0_wp
    ok = ok .and. all(ints(1:3) >= 1 .and. ints(1:3) <= 4) &
        .and. all(ints(4:6) >= 1)
  end function design_is_valid

  !> Evaluate one design up to the coefficients of y3 (its extremes are
  !> searched for a whole block of designs, then finish_design); p1, p2,
  !> p3, c3 get its live modes (rest NaN).
  pure subroutine evaluate_design(row, ints, options, kl, sigma, g, &
      memory, res, p1, p2, p3, c3)
    real(wp), intent(in) :: row(n_real)
    integer, intent(in) :: ints(6), options(4)
    real(wp), intent(in) :: kl(:, :), sigma(:, :), g(:, :)
    !> Work shared with the batch's previous design (see batch_memory).
    type(batch_memory), intent(inout) :: memory
    type(design_result), intent(out) :: res
    real(wp), intent(out) :: p1(:), p2(:), p3(:), c3(:)
    real(wp) :: a1, a2, a3, m2_psi, m2_v0, xi1, xi2, xi3, xi_load, flex
    real(wp) :: l2_freq, horizon, s1, s2, s3, gain, nan
    real(wp) :: x1v(size(p1)), x2v(size(p1)), x3v(size(p1))
    real(wp) :: load(size(p1)), amp(size(p1))
    logical :: missed, has_lc
    integer :: n1, n2, n3, e1, e2, e3

    nan = ieee_value(0.0_wp, ieee_quiet_nan)
    p1 = nan
    p2 = nan
    p3 = nan
    c3 = nan
    res%t1 = nan; res%v_impact = nan; res%psi = nan; res%v0 = nan
    res%r = nan; res%y3_max = nan; res%t_max = nan; res%y3_min = nan
    res%t_min = nan; res%m1 = nan; res%m2 = nan; res%m3 = nan
    res%at_end = .false.
    res%max_tied = .false.
    res%min_tied = .false.
    if (.not. design_is_valid(row, ints)) then
      res%status = status_invalid_input
      return
    end if
    e1 = ints(1); e2 = ints(2); e3 = ints(3)
    n1 = ints(4); n2 = ints(5); n3 = ints(6)
    call member_constants(row(1), row(2), row(3), row(4), row(5), &
        res%m1, a1)
    call member_constants(row(7), row(8), row(9), row(10), row(11), &
        res%m2, a2)
    call member_constants(row(14), row(15), row(16), row(17), row(18), &
        res%m3, a3)
    xi1 = row(6) / row(1)
    xi2 = row(12) / row(7)
    xi3 = row(19) / row(14)
    call point_values(memory, 1, e1, n1, xi1, kl, sigma, g, x1v)
    call point_values(memory, 2, e2, n2, xi2, kl, sigma, g, x2v)
    call point_values(memory, 3, e3, n3, xi3, kl, sigma, g, x3v)
    p1(1:n1) = frequency(kl(1:n1, e1), a1, row(1))
    p3(1:n3) = frequency(kl(1:n3, e3), a3, row(14))
    has_lc = row(13) > 0.0_wp
    l2_freq = row(7)
    if (has_lc .and. options(3) /= 0) l2_freq = row(13)
    p2(1:n2) = frequency(kl(1:n2, e2), a2, l2_freq)
    m2_psi = res%m2
    m2_v0 = res%m2
    if (has_lc .and. options(3) == 2) m2_psi = res%m2 * row(13) / row(7)
    if (has_lc .and. options(3) /= 1) m2_v0 = res%m2 * row(13) / row(7)

    xi_load = xi1
    if (options(4) == 0 .and. e1 == clamped_free) xi_load = 1.0_wp
    flex = static_flexibility(e1, xi_load)
    if (.not. (flex > 0.0_wp)) then
      res%status = status_invalid_input
      call clear(res, p1, p2, p3, c3, nan)
      return
    end if
    if (any(memory%upper_key /= [row(1:6), row(20), row(23)]) .or. &
        any(memory%upper_ints /= [e1, n1, options(1), options(4)])) then
      call point_values(memory, 4, e1, n1, xi_load, kl, sigma, g, load)
      call release_amplitudes(row(20), load(1:n1), kl(1:n1, e1), flex, &
          amp(1:n1))
      amp(1:n1) = amp(1:n1) * x1v(1:n1)
      horizon = 2.0_wp * pi / p1(1)
      call first_impact(amp(1:n1), p1(1:n1), row(23), horizon, &
          memory%t1, memory%missed)
      if (.not. memory%missed) memory%v_impact = impact_velocity( &
          amp(1:n1), p1(1:n1), memory%t1, options(1) == 1)
      memory%upper_key = [row(1:6), row(20), row(23)]
      memory%upper_ints = [e1, n1, options(1), options(4)]
    end if
    missed = memory%missed
    if (missed) then
      res%status = status_no_impact
      call clear(res, p1, p2, p3, c3, nan)
      return
    end if
    res%t1 = memory%t1
    res%v_impact = memory%v_impact
    s1 = sum(x1v(1:n1)**2)
    s2 = sum(x2v(1:n2)**2)
    s3 = sum(x3v(1:n3)**2)
    res%psi = impulse(row(21), res%v_impact, s1, res%m1, s2, m2_psi, s3, &
        res%m3)
    res%v0 = separator_velocity(res%psi, s2, m2_v0)
    if (options(2) == 1) then
      gain = res%psi / res%m3
    else
      gain = res%v0 / row(14)
    end if
    call lower_coefficients(gain, x3v(1:n3), p3(1:n3), c3(1:n3))
    res%r = mass_ratio(m2_v0, s2, res%m3, s3)
    res%m2 = m2_psi
  end subroutine evaluate_design

  !> A design's status once the extremes of y3 are in res (model_extremes;
  !> resolved false when that search gave up): unresolved or not finite
  !> designs get NaN results.
  pure subroutine finish_design(res, resolved, p1, p2, p3, c3)
    type(design_result), intent(inout) :: res
    logical, intent(in) :: resolved
    real(wp), intent(inout) :: p1(:), p2(:), p3(:), c3(:)
    real(wp) :: nan

    if (res%status /= status_ok) return
    nan = ieee_value(0.0_wp, ieee_quiet_nan)
    if (.not. resolved) then
      res%status = status_unresolved
      call clear(res, p1, p2, p3, c3, nan)
    else if (.not. all(ieee_is_finite([res%t1, res%v_impact, res%psi, &
        res%v0, res%r, res%y3_max, res%t_max, res%y3_min, res%t_min, &
        res%m1, res%m2, res%m3]))) then
      res%status = status_not_finite
      call clear(res, p1, p2, p3, c3, nan)
    end if
  end subroutine finish_design

  !> X_j(xi), j = 1..n, of end condition `end`: point `which` of the
  !> memory, recomputed only when (end, n, xi) changed.
  pure subroutine point_values(memory, which, end, n, xi, kl, sigma, g, &
      values)
    type(batch_memory), intent(inout) :: memory
    integer, intent(in) :: which, end, n
    real(wp), intent(in) :: xi, kl(:, :), sigma(:, :), g(:, :)
    real(wp), intent(out) :: values(:)
    integer :: j

    if (.not. allocated(memory%point_values)) &
        allocate(memory%point_values(size(kl, 1), 4))
    if (any(memory%point_key(:, which) /= [end, n]) .or. &
        memory%point_xi(which) /= xi) then
      do j = 1, n
        memory%point_values(j, which) = mode_value(end, kl(j, end), &
            sigma(j, end), g(j, end), xi)
      end do
      memory%point_key(:, which) = [end, n]
      memory%point_xi(which) = xi
    end if
    values(1:n) = memory%point_values(1:n, which)
  end subroutine point_values

  !> NaN results for a design that failed (its status is kept).
  pure subroutine clear(res, p1, p2, p3, c3, nan)
    type(design_result), intent(inout) :: res
    real(wp), intent(inout) :: p1(:), p2(:), p3(:), c3(:)
    real(wp), intent(in) :: nan

    res%t1 = nan; res%v_impact = nan; res%psi = nan; res%v0 = nan
    res%r = nan; res%y3_max = nan; res%t_max = nan; res%y3_min = nan
    res%t_min = nan; res%m1 = nan; res%m2 = nan; res%m3 = nan
    res%at_end = .false.
    res%max_tied = .false.
    res%min_tied = .false.
    p1 = nan
    p2 = nan
    p3 = nan
    c3 = nan
  end subroutine clear

  !> The extremes of a chunk's designs (batch columns first..last, whose
  !> results are res(1:last-first+1)), searched together, and every
  !> design's figures written to the batch's columns (as evaluate_batch
  !> and evaluate_batch_given of model_api both end a chunk).
  subroutine finish_chunk(first, last, res, search, n3, tau, ws, t1, &
      v_impact, psi, v0, r, y3_max, t_max, y3_min, t_min, at_end, &
      max_tied, min_tied, status, m1, m2, m3, p1, p2, p3, c3)
    integer, intent(in) :: first, last
    type(design_result), intent(inout) :: res(:)
    !> Which designs' extremes are searched; lower-contact mode counts,
    !> windows (s).
    logical, intent(in) :: search(:)
    integer, intent(in) :: n3(:)
    real(wp), intent(in) :: tau(:)
    type(extremes_workspace), intent(inout) :: ws
    real(wp), intent(inout) :: t1(:), v_impact(:), psi(:), v0(:), r(:)
    real(wp), intent(inout) :: y3_max(:), t_max(:), y3_min(:), t_min(:)
    real(wp), intent(inout) :: m1(:), m2(:), m3(:)
    integer, intent(inout) :: at_end(:), max_tied(:), min_tied(:)
    integer, intent(inout) :: status(:)
    real(wp), intent(inout) :: p1(:, :), p2(:, :), p3(:, :), c3(:, :)
    logical :: resolved(size(res)), ends(size(res)), ties(size(res), 2)
    integer :: i, k

    k = last - first + 1
    call extremes(c3(:, first:last), p3(:, first:last), n3(1:k), &
        tau(1:k), search(1:k), ws, y3_max(first:last), &
        t_max(first:last), y3_min(first:last), t_min(first:last), &
        ends(1:k), ties(1:k, 1), ties(1:k, 2), resolved(1:k))
    do i = first, last
      k = i - first + 1
      if (search(k)) then
        res(k)%y3_max = y3_max(i)
        res(k)%t_max = t_max(i)
        res(k)%y3_min = y3_min(i)
        res(k)%t_min = t_min(i)
        res(k)%at_end = ends(k)
        res(k)%max_tied = ties(k, 1)
        res(k)%min_tied = ties(k, 2)
      end if
      call finish_design(res(k), resolved(k), p1(:, i), p2(:, i), &
          p3(:, i), c3(:, i))
      t1(i) = res(k)%t1
      v_impact(i) = res(k)%v_impact
      psi(i) = res(k)%psi
      v0(i) = res(k)%v0
      r(i) = res(k)%r
      y3_max(i) = res(k)%y3_max
      t_max(i) = res(k)%t_max
      y3_min(i) = res(k)%y3_min
      t_min(i) = res(k)%t_min
      m1(i) = res(k)%m1
      m2(i) = res(k)%m2
      m3(i) = res(k)%m3
      at_end(i) = merge(1, 0, res(k)%at_end)
      max_tied(i) = merge(1, 0, res(k)%max_tied)
      min_tied(i) = merge(1, 0, res(k)%min_tied)
      status(i) = res(k)%status
    end do
  end subroutine finish_chunk

end module model_batch
