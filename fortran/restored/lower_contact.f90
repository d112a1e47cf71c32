!> From the impulse to the lower contact: the separator's mid-span
!> velocity, the lower contact's tip history up to TAU, and the closing
!> ratios of the listing (statements 350-660).
!>
!> The separator is a clamped-clamped beam struck at mid-span; its
!> mid-span velocity TY2DT starts the lower contact, a cantilever, whose
!> tip then moves as TY3(T) = sum TY2DT*C3(I)**2*SIN(P3(I)*T)/(XL3*P3(I)).
module contactsep_lower_contact
  use contactsep_kinds, only: wp
  use contactsep_constants, only: listing_tau
  use contactsep_status, only: message_length, status_ok, &
      status_history_stalled, status_history_full, real_text, integer_text
  implicit none
  private
  public :: corrected_separator_mass, separator_midspan_velocity
  public :: lower_contact_tip, lower_contact_history, closing_ratios

  !> End of the history: the listing's TAU = 0.060 s.
  real(wp), parameter, public :: tau = listing_tau

contains

  !> Separator mass rescaled to the equivalent length XL2C, which makes
  !> the ideal clamped beam ring at the measured frequency.
  !>
  !> The listing applies it after the impulse, so EY uses the mass from
  !> the real length XL2 and TY2DT, BETA, MR1, MR3 the corrected one.
  pure function corrected_separator_mass(wm2, xl2c, xl2) result(corrected)
    real(wp), intent(in) :: wm2, xl2c, xl2
    real(wp) :: corrected

    corrected = wm2 * (xl2c / xl2)
  end function corrected_separator_mass

  !> Mid-span velocity TY2DT of the separator after impulse ey; wm2 is
  !> the corrected mass and c2 the mode values X(L2/2).
  pure function separator_midspan_velocity(ey, wm2, c2) result(ty2dt)
    real(wp), intent(in) :: ey, wm2
    real(wp), intent(in) :: c2(:)
    real(wp) :: ty2dt, y2dt
    integer :: i

    ty2dt = 0.0_wp
    do i = 1, size(c2)
      y2dt = (ey / wm2) * c2(i)**2
      ty2dt = ty2dt + y2dt
    end do
  end function separator_midspan_velocity

  !> Tip displacement TY3 of the lower contact at time t (loop 500).
  pure function lower_contact_tip(ty2dt, c3, p3, xl3, t) result(ty3)
    real(wp), intent(in) :: ty2dt
    !> Tip mode values X(L3) and frequencies P3 of the lower contact.
    real(wp), intent(in) :: c3(:), p3(:)
    real(wp), intent(in) :: xl3, t
    real(wp) :: ty3, y3
    integer :: i

    ty3 = 0.0_wp
    do i = 1, size(c3)
      y3 = ty2dt * (c3(i)**2 * sin(p3(i) * t)) / (xl3 * p3(i))
      ty3 = ty3 + y3
    end do
  end function lower_contact_tip

  !> History lines T, TY3 for T = 0, DELT, 2*DELT, ... while T < t_end
  !> (the listing's TAU unless a caller asks for another window).
  !>
  !> T is accumulated as the listing does (T = T + DELT), so its rounding
  !> and the last line match.  The listing loops forever when T + DELT
  !> does not advance T; that is refused, as is a history longer than
  !> history has rows.  Lines before the failure are kept.
  subroutine lower_contact_history(ty2dt, c3, p3, xl3, delt, t_end, &
      history, n_history, status, message)
    real(wp), intent(in) :: ty2dt
    real(wp), intent(in) :: c3(:), p3(:)
    real(wp), intent(in) :: xl3
    !> The step from card 4 (the search's halving does not carry over).
    real(wp), intent(in) :: delt
    !> End of the window (TAU in the listing).
    real(wp), intent(in) :: t_end
    real(wp), intent(inout) :: history(:, :)
    integer, intent(out) :: n_history
    integer, intent(out) :: status
    character(len=message_length), intent(out) :: message
    real(wp) :: t, previous

    status = status_ok
    message = ''
    n_history = 0
    t = 0.0_wp
    do
      if (n_history >= size(history, 1)) then
        status = status_history_full
        message = 'the history to TAU = ' // real_text(t_end) &
            // ' needs more than ' // integer_text(size(history, 1)) &
            // ' lines (max_history) with DELT = ' // real_text(delt)
        return
      end if
      n_history = n_history + 1
      history(n_history, :) = [t, lower_contact_tip(ty2dt, c3, p3, xl3, t)]
      previous = t
      t = t + delt
      ! IF (T - TAU) 520,600,600: a NaN T ends the history too.
      if (.not. (t - t_end < 0.0_wp)) exit
      if (.not. (t > previous)) then
        status = status_history_stalled
        message = 'the history cannot reach TAU = ' // real_text(t_end) &
            // ': T + DELT does not advance T = ' // real_text(previous) &
            // ' with DELT = ' // real_text(delt) // ' (DELT must be > 0)'
        return
      end if
    end do
  end subroutine lower_contact_history

  !> Closing ratios: GR = H2/XL2, BETA = WM/(WM2+WM3), MR1 = WM2/WM and
  !> MR3 = WM2/WM3, with the corrected separator mass wm2.
  pure subroutine closing_ratios(h2, xl2, wm, wm2, wm3, gr, beta, mr1, mr3)
    real(wp), intent(in) :: h2, xl2, wm, wm2, wm3
    real(wp), intent(out) :: gr, beta, mr1, mr3

    gr = h2 / xl2
    beta = wm / (wm2 + wm3)
    mr1 = wm2 / wm
    mr3 = wm2 / wm3
  end subroutine closing_ratios

end module contactsep_lower_contact
