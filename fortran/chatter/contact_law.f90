!> The force law of one or two contacts of the Hertz family, with the
!> memory a plastic contact needs (docs/chatter.md, "Contact laws"):
!>
!> * Hertz: F_e = k delta^{3/2} (delta the penetration, k the Hertz
!>   constant (4/3) E* sqrt(R));
!> * Thornton (1997), elastic-perfectly-plastic sphere on a flat: Hertz
!>   until the largest Hertz pressure 2 E* a / (pi R) reaches the
!>   yield pressure p_y at delta_y = (pi p_y / (2 E*))^2 R (force F_y), then
!>   F_e = F_y + pi p_y R (delta - delta_y) on loading (a new largest
!>   penetration delta_m); unloading and reloading below delta_m are
!>   elastic Hertz with the enlarged radius R_p = 4 E* a_m^3 / (3 F_m)
!>   (a_m^2 = R delta_m, F_m the force at delta_m) from the plastic
!>   offset delta_p = delta_m - a_m^2 / R_p: F_e = (4/3) E* sqrt(R_p)
!>   (delta - delta_p)^{3/2}, 0 below delta_p.
!>
!> * a cylindrical button (line contact): F_e = k delta, k = (pi/4) E* L
!>   (law%linear; elastic only).
!>
!> Either takes the damping factor of Hunt and Crossley (and Flores's
!> calibration of it): F = max(F_e (1 + chi delta'), 0).  The elastic
!> part stores (2/5) F_e (delta - delta_p) (the curve it unloads on);
!> the plastic work of a contact is a function of delta_m alone,
!> W_p = int_0^{delta_m} F_envelope - (2/5) F_m (delta_m - delta_p),
!> updated where delta_m grows.  The damping's work is summed by the
!> steppers (each kick's exact change of kinetic energy, its damping
!> part).  Twin: contactsep/chatter/contacts.py (ContactLaw).
module chatter_contact_law
  use contactsep_kinds, only: wp
  implicit none
  private
  public :: contact_law, law_setup, law_elastic_force, law_force
  public :: law_elastic_slope
  public :: law_energy, law_remember, law_plastic_work, max_contacts

  !> Contacts a law keeps memory for.
  integer, parameter :: max_contacts = 2
  real(wp), parameter :: pi = 3.14159265358979323846_wp

  type :: contact_law
    !> Hertz constant k (lb/in^1.5) and damping chi (s/in).
    real(wp) :: stiffness = 0.0_wp, chi = 0.0_wp
    !> A line contact (cylindrical button): F_e = k delta (k in lb/in).
    logical :: linear = .false.
    !> Thornton: effective modulus E* (psi), radius R (in), yield
    !> pressure p_y (psi), and what follows from them.
    logical :: plastic = .false.
    real(wp) :: e_star = 0.0_wp, radius = 0.0_wp, pressure = 0.0_wp
    real(wp) :: yield_depth = 0.0_wp, yield_force = 0.0_wp
    real(wp) :: slope = 0.0_wp
    !> Each contact's largest penetration, its unloading constant
    !> (4/3) E* sqrt(R_p), plastic offset delta_p and plastic work.
    real(wp) :: depth_max(max_contacts) = 0.0_wp
    real(wp) :: unload_k(max_contacts) = 0.0_wp
    real(wp) :: offset(max_contacts) = 0.0_wp
    real(wp) :: work(max_contacts) = 0.0_wp
  end type contact_law

contains

  !> A law: Hertz constant k, damping chi; yield pressure p_y > 0 makes
  !> it Thornton's with E* and R (k must be (4/3) E* sqrt(R)).
  pure subroutine law_setup(law, stiffness, chi, pressure, e_star, &
      radius, linear)
    type(contact_law), intent(out) :: law
    real(wp), intent(in) :: stiffness, chi, pressure, e_star, radius
    !> A line contact (F_e = k delta); not with a yield pressure.
    logical, intent(in), optional :: linear
    real(wp) :: contact_radius

    law%stiffness = stiffness
    law%chi = chi
    if (present(linear)) law%linear = linear
    if (law%linear) return
    law%plastic = pressure > 0.0_wp
    if (.not. law%plastic) return
    law%e_star = e_star
    law%radius = radius
    law%pressure = pressure
    contact_radius = pi * pressure * radius / (2.0_wp * e_star)
    law%yield_depth = contact_radius**2 / radius
    law%yield_force = stiffness * law%yield_depth * sqrt(law%yield_depth)
    law%slope = pi * pressure * radius
  end subroutine law_setup

  !> The force of contact c on the loading envelope at depth (> 0).
  pure function envelope(law, depth) result(force)
    type(contact_law), intent(in) :: law
    real(wp), intent(in) :: depth
    real(wp) :: force

    if (law%linear) then
      force = law%stiffness * depth
    else if (.not. law%plastic .or. depth <= law%yield_depth) then
      force = law%stiffness * depth * sqrt(depth)
    else
      force = law%yield_force + law%slope * (depth - law%yield_depth)
    end if
  end function envelope

  !> The elastic (undamped) force F_e (lb) of contact c at penetration
  !> depth (in; <= 0: none); past the remembered largest penetration
  !> the envelope's.
  pure function law_elastic_force(law, c, depth) result(force)
    type(contact_law), intent(in) :: law
    integer, intent(in) :: c
    real(wp), intent(in) :: depth
    real(wp) :: force, over

    force = 0.0_wp
    if (.not. depth > 0.0_wp) return
    if (.not. law%plastic .or. depth >= law%depth_max(c) &
        .or. law%depth_max(c) <= law%yield_depth) then
      force = envelope(law, depth)
      return
    end if
    over = depth - law%offset(c)
    if (over > 0.0_wp) force = law%unload_k(c) * over * sqrt(over)
  end function law_elastic_force

  !> dF_e/d delta (lb/in) of contact c at depth, on the branch
  !> law_elastic_force takes there (the series solve's Newton steps).
  pure function law_elastic_slope(law, c, depth) result(slope)
    type(contact_law), intent(in) :: law
    integer, intent(in) :: c
    real(wp), intent(in) :: depth
    real(wp) :: slope, over

    slope = 0.0_wp
    if (.not. depth > 0.0_wp) return
    if (.not. law%plastic .or. depth >= law%depth_max(c) &
        .or. law%depth_max(c) <= law%yield_depth) then
      if (law%linear) then
        slope = law%stiffness
      else if (.not. law%plastic .or. depth <= law%yield_depth) then
        slope = 1.5_wp * law%stiffness * sqrt(depth)
      else
        slope = law%slope
      end if
      return
    end if
    over = depth - law%offset(c)
    if (over > 0.0_wp) slope = 1.5_wp * law%unload_k(c) * sqrt(over)
  end function law_elastic_slope

  !> The force (lb) with the damping factor: max(F_e (1 + chi delta'),
  !> 0), delta' = -rate (in/s) the penetration's rate.
  pure function law_force(law, c, depth, rate) result(force)
    type(contact_law), intent(in) :: law
    integer, intent(in) :: c
    real(wp), intent(in) :: depth, rate
    real(wp) :: force

    force = law_elastic_force(law, c, depth)
    if (law%chi /= 0.0_wp .and. force > 0.0_wp) force = max(force &
        * (1.0_wp - law%chi * rate), 0.0_wp)
  end function law_force

  !> The elastic energy (in lb) contact c stores at depth: the work its
  !> unloading curve gives back, (2/5) F_e (delta - delta_p).
  pure function law_energy(law, c, depth) result(total)
    type(contact_law), intent(in) :: law
    integer, intent(in) :: c
    real(wp), intent(in) :: depth
    real(wp) :: total, offset

    total = 0.0_wp
    if (.not. depth > 0.0_wp) return
    if (law%linear) then
      total = 0.5_wp * law%stiffness * depth**2
      return
    end if
    if (.not. law%plastic) then
      ! Hertz's (2/5) k delta^{5/2}, as the steppers always wrote it
      total = 0.4_wp * law%stiffness * depth**2.5_wp
      return
    end if
    offset = 0.0_wp
    if (law%plastic .and. depth < law%depth_max(c) .and. &
        law%depth_max(c) > law%yield_depth) offset = law%offset(c)
    if (law%plastic .and. depth >= law%depth_max(c) .and. &
        depth > law%yield_depth) then
      ! ahead of the memory: the unloading curve from this depth
      offset = unloading_offset(law, depth)
    end if
    if (depth > offset) total = 0.4_wp * law_elastic_force(law, c, depth) &
        * (depth - offset)
  end function law_energy

  !> delta_p of the unloading curve from a largest penetration depth
  !> (> delta_y): delta - a^2 / R_p, a^2 = R delta, R_p = 4 E* a^3 /
  !> (3 F).
  pure function unloading_offset(law, depth) result(offset)
    type(contact_law), intent(in) :: law
    real(wp), intent(in) :: depth
    real(wp) :: offset, a2, force, r_p

    a2 = law%radius * depth
    force = envelope(law, depth)
    r_p = 4.0_wp * law%e_star * a2 * sqrt(a2) / (3.0_wp * force)
    offset = depth - a2 / r_p
  end function unloading_offset

  !> Remember contact c's penetration depth: a new largest one moves
  !> its unloading curve and plastic work (Thornton only).
  pure subroutine law_remember(law, c, depth)
    type(contact_law), intent(inout) :: law
    integer, intent(in) :: c
    real(wp), intent(in) :: depth
    real(wp) :: a2, force, r_p, over, loading

    if (.not. law%plastic) return
    if (.not. depth > law%depth_max(c)) return
    law%depth_max(c) = depth
    if (depth <= law%yield_depth) return
    a2 = law%radius * depth
    force = envelope(law, depth)
    r_p = 4.0_wp * law%e_star * a2 * sqrt(a2) / (3.0_wp * force)
    law%unload_k(c) = 4.0_wp / 3.0_wp * law%e_star * sqrt(r_p)
    law%offset(c) = depth - a2 / r_p
    ! the envelope's work to depth, less what unloading gives back
    over = depth - law%yield_depth
    loading = 0.4_wp * law%yield_force * law%yield_depth &
        + law%yield_force * over + 0.5_wp * law%slope * over**2
    law%work(c) = loading - 0.4_wp * force * (depth - law%offset(c))
  end subroutine law_remember

  !> The plastic work (in lb) of the first k contacts so far.
  pure function law_plastic_work(law, k) result(total)
    type(contact_law), intent(in) :: law
    integer, intent(in) :: k

    real(wp) :: total

    total = 0.0_wp
    if (law%plastic) total = sum(law%work(1:k))
  end function law_plastic_work

end module chatter_contact_law
