!> The general model (eq. 23) on a design whose modes are given (issue 27:
!> a Timoshenko beam, elastic supports or point masses, computed by
!> contactsep.beams): the same arithmetic as model_batch's
!> evaluate_design, with each member's dimensionless eigenvalues
!> b_j = omega_j L^2 sqrt(rho A/EI) (= (k_jL)^2 of the thesis's beams),
!> its mode values at the contact points and the upper contact's static
!> flexibility at the load point taken as inputs instead of the closed
!> forms of beam_modes.f90.  The thesis's designs keep evaluate_design
!> (and its batch memory): this file adds a path, it changes none.
module model_given
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use contactsep_kinds, only: wp
  use model_status, only: status_ok, status_invalid_input, status_no_impact
  use model_batch, only: design_result, design_is_valid, n_real, clear
  use model_members, only: member_constants
  use model_impact, only: first_impact, impact_velocity
  use model_responses, only: impulse, separator_velocity, &
      lower_coefficients, mass_ratio
  implicit none
  private
  public :: evaluate_given_design

  real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp

contains

  !> Evaluate one design up to the coefficients of y3 from its given
  !> modes (then model_extremes and finish_design, as for any design).
  pure subroutine evaluate_given_design(row, ints, options, b, values, &
      flex, res, p1, p2, p3, c3)
    real(wp), intent(in) :: row(n_real)
    integer, intent(in) :: ints(6), options(4)
    !> b_j of members 1, 2, 3 (columns); mode values X1j(x1), X2j(x2),
    !> X3j(x3) and X1j at the upper contact's load point (columns),
    !> normalised to a generalised mass of the bare member, rho A L.
    real(wp), intent(in) :: b(:, :), values(:, :)
    !> G(a) = y(a) EI/(F L^3) of the upper contact at its load point.
    real(wp), intent(in) :: flex
    type(design_result), intent(out) :: res
    real(wp), intent(out) :: p1(:), p2(:), p3(:), c3(:)
    real(wp) :: a1, a2, a3, m2_psi, m2_v0, l2_freq, horizon, s1, s2, s3
    real(wp) :: gain, nan, coef(size(p1))
    logical :: has_lc, missed
    integer :: n1, n2, n3

    nan = ieee_value(0.0_wp, ieee_quiet_nan)
    res%status = status_ok
    call clear(res, p1, p2, p3, c3, nan)
    if (.not. design_is_valid(row, ints)) then
      res%status = status_invalid_input
      return
    end if
    n1 = ints(4); n2 = ints(5); n3 = ints(6)
    call member_constants(row(1), row(2), row(3), row(4), row(5), &
        res%m1, a1)
    call member_constants(row(7), row(8), row(9), row(10), row(11), &
        res%m2, a2)
    call member_constants(row(14), row(15), row(16), row(17), row(18), &
        res%m3, a3)
    ! p_j = b_j a / L^2; L_c scales the separator's as it scales k_jL's
    p1(1:n1) = b(1:n1, 1) * (a1 / row(1)**2)
    p3(1:n3) = b(1:n3, 3) * (a3 / row(14)**2)
    has_lc = row(13) > 0.0_wp
    l2_freq = row(7)
    if (has_lc .and. options(3) /= 0) l2_freq = row(13)
    p2(1:n2) = b(1:n2, 2) * (a2 / l2_freq**2)
    m2_psi = res%m2
    m2_v0 = res%m2
    if (has_lc .and. options(3) == 2) m2_psi = res%m2 * row(13) / row(7)
    if (has_lc .and. options(3) /= 1) m2_v0 = res%m2 * row(13) / row(7)
    if (.not. (flex > 0.0_wp) .or. .not. all(b(1:n1, 1) > 0.0_wp)) then
      res%status = status_invalid_input
      call clear(res, p1, p2, p3, c3, nan)
      return
    end if
    ! A_j X_j(x1), A_j = y_s X_j(a) / (b_j^2 G(a)): the exact modal
    ! coefficients of the static shape (A-(7) with (k_jL)^4 = b_j^2)
    coef(1:n1) = row(20) * values(1:n1, 4) / (b(1:n1, 1)**2 * flex) &
        * values(1:n1, 1)
    horizon = 2.0_wp * pi / p1(1)
    call first_impact(coef(1:n1), p1(1:n1), row(23), horizon, res%t1, &
        missed)
    if (missed) then
      res%status = status_no_impact
      call clear(res, p1, p2, p3, c3, nan)
      return
    end if
    res%v_impact = impact_velocity(coef(1:n1), p1(1:n1), res%t1, &
        options(1) == 1)
    s1 = sum(values(1:n1, 1)**2)
    s2 = sum(values(1:n2, 2)**2)
    s3 = sum(values(1:n3, 3)**2)
    res%psi = impulse(row(21), res%v_impact, s1, res%m1, s2, m2_psi, s3, &
        res%m3)
    res%v0 = separator_velocity(res%psi, s2, m2_v0)
    if (options(2) == 1) then
      gain = res%psi / res%m3
    else
      gain = res%v0 / row(14)
    end if
    call lower_coefficients(gain, values(1:n3, 3), p3(1:n3), c3(1:n3))
    res%r = mass_ratio(m2_v0, s2, res%m3, s3)
    res%m2 = m2_psi
  end subroutine evaluate_given_design

end module model_given
