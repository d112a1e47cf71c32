!> Hertz contact between the modal members by Strang splitting: half
!> kick of the contact forces, the exact modal flow over dt, half kick.
!> With the static correction (cmat /= 0) the forces are those of the
!> Hertz elements in series with the truncated modes' residual
!> flexibility (chatter_hertz_series); cmat = 0 is the plain truncation,
!> bit for bit.  Thornton's law takes the series solve of its own force
!> (series_law_forces) and remembers the elements' depths.
!> Twin: contactsep/chatter/steppers.py.
module chatter_hertz
  use contactsep_kinds, only: wp
  use chatter_status, only: status_ok, status_energy_bound, &
      status_interrupted
  use chatter_stop, only: stop_requested, stop_check_every
  use chatter_hertz_series, only: series_forces, series_energy, &
      series_law_forces, series_law_energy
  use chatter_contact_law, only: contact_law, law_force, law_energy, &
      law_elastic_force, law_remember, law_plastic_work
  implicit none
  private
  public :: hertz

contains

  !> F = F_e (1 + chi delta'), F >= 0, delta = -gap, F_e the law's
  !> elastic force (chatter_contact_law); the contact's rate h v is
  !> formed only where a contact is closed.
  pure subroutine contact_forces(n, k, law, gap, ht, v, force)
    integer, intent(in) :: n, k
    type(contact_law), intent(in) :: law
    real(wp), intent(in) :: gap(k), ht(n, k), v(n)
    real(wp), intent(out) :: force(k)
    integer :: i

    do i = 1, k
      if (gap(i) < 0.0_wp) then
        force(i) = law_force(law, i, -gap(i), dot_product(ht(:, i), v))
      else
        force(i) = 0.0_wp
      end if
    end do
  end subroutine contact_forces

  !> The forces of the Hertz elements in series with cmat (see
  !> chatter_hertz_series): Flores's factor max(1 - chi u, 0), u = h v
  !> the rate of the modal gap, scales each element's stiffness.
  pure subroutine series_contact_forces(n, k, stiffness, chi, cmat, gap, &
      ht, v, force, linear)
    integer, intent(in) :: n, k
    logical, intent(in) :: linear
    real(wp), intent(in) :: stiffness, chi, cmat(k, k), gap(k), ht(n, k)
    real(wp), intent(in) :: v(n)
    real(wp), intent(out) :: force(k)
    real(wp) :: stiff(k)
    integer :: i

    if (all(gap >= 0.0_wp)) then
      force = 0.0_wp
      return
    end if
    stiff = stiffness
    if (chi /= 0.0_wp) then
      do i = 1, k
        stiff(i) = stiffness * max(1.0_wp - chi &
            * dot_product(ht(:, i), v), 0.0_wp)
      end do
    end if
    call series_forces(k, stiff, cmat, gap, force, linear)
  end subroutine series_contact_forces

  !> series_contact_forces for Thornton's law (law%plastic): the
  !> elements' forces and depths with Flores's factor max(1 - chi u, 0)
  !> (chatter_hertz_series's series_law_forces).
  pure subroutine series_law_contact_forces(n, k, law, cmat, gap, ht, v, &
      force, depth)
    integer, intent(in) :: n, k
    type(contact_law), intent(in) :: law
    real(wp), intent(in) :: cmat(k, k), gap(k), ht(n, k), v(n)
    real(wp), intent(out) :: force(k), depth(k)
    real(wp) :: factor(k)
    integer :: i

    factor = 1.0_wp
    if (law%chi /= 0.0_wp .and. any(gap < 0.0_wp)) then
      do i = 1, k
        factor(i) = max(1.0_wp - law%chi * dot_product(ht(:, i), v), &
            0.0_wp)
      end do
    end if
    call series_law_forces(k, law, factor, cmat, gap, force, depth)
  end subroutine series_law_contact_forces

  !> Integrate `steps` steps of dt; sample every `stride` steps.
  !>
  !> The gap after the flow is the next step's gap before it (a kick
  !> changes v, not q), so one 2 x n product a step finds both; kicks
  !> and contact rates cost only while a contact is closed.
  !> Hard bounds (issue 31): the run stops with status_energy_bound
  !> when the energy at a sample or a stop check exceeds energy_bound
  !> (or is not a number), and with status_interrupted when
  !> chatter_stop's flag is set; the samples not reached keep t = -1.
  !> The energy book: dissipated = the damping's work (each kick's
  !> exact change of kinetic energy, its damping part) and the plastic
  !> work (chatter_contact_law); stored = the contacts' elastic energy
  !> at the end.
  subroutine hertz(n, k, m, p, h, g0, cmat, q, v, law, &
      dt, steps, stride, samples, t_out, g_out, e_out, p_out, first, &
      energy_bound, status, book)
    integer, intent(in) :: n, k
    !> cmat: the series flexibilities (in/lb; 0: the plain truncation).
    real(wp), intent(in) :: m(n), p(n), h(k, n), g0(k), cmat(k, k)
    real(wp), intent(inout) :: q(n), v(n)
    !> The force law (Hertz constant, damping chi, Thornton's yield)
    !> and its memory.
    type(contact_law), intent(inout) :: law
    real(wp), intent(in) :: dt
    integer, intent(in) :: steps, stride, samples
    !> Sampled times, gaps (with the correction, the physical gaps
    !> g + C lambda), energy (with the contacts'), and impulses
    !> (force x dt) summed over each sample.
    real(wp), intent(out) :: t_out(samples), g_out(k, samples)
    real(wp), intent(out) :: e_out(samples), p_out(k, samples)
    !> Contact 1's first episode: the start of its first step with a
    !> force, and the impulse of its consecutive steps with one.
    real(wp), intent(out) :: first(2)
    !> The energy's hard bound (in lb) and how the run ended.
    real(wp), intent(in) :: energy_bound
    integer, intent(out) :: status
    !> Dissipated energy and the contacts' stored energy (in lb).
    real(wp), intent(out) :: book(2)
    real(wp) :: c(n), sine_over_p(n), p_sine(n), ht(n, k), half_kick(n, k)
    real(wp) :: force(k), gap(k), qn(n), damped_work
    integer :: step, i, sample, episode
    logical :: series

    c = cos(p * dt)
    sine_over_p = sin(p * dt) / p
    p_sine = p * sin(p * dt)
    ht = transpose(h)
    do i = 1, k
      half_kick(:, i) = 0.5_wp * dt * ht(:, i) / m
    end do
    series = any(cmat /= 0.0_wp)
    damped_work = 0.0_wp
    p_out = 0.0_wp
    first = -1.0_wp
    episode = 0
    status = status_ok
    t_out = -1.0_wp
    g_out = 0.0_wp
    e_out = 0.0_wp
    t_out(1) = 0.0_wp
    gap = gaps()
    call remember()
    g_out(:, 1) = gap
    if (series) then
      call forces(force)
      g_out(:, 1) = gap + matmul(cmat, force)
    end if
    e_out(1) = energy()
    do step = 1, steps
      call forces(force)
      sample = (step - 1) / stride + 2
      if (sample <= samples) p_out(:, sample) = p_out(:, sample) &
          + force * dt
      if (force(1) > 0.0_wp .and. episode == 0) then
        episode = 1
        first(1) = (step - 1) * dt
        first(2) = 0.0_wp
      end if
      if (episode == 1) then
        if (force(1) > 0.0_wp) then
          first(2) = first(2) + force(1) * dt
        else
          episode = 2
        end if
      end if
      call kick(v)
      qn = q * c + v * sine_over_p
      v = v * c - q * p_sine
      q = qn
      gap = gaps()
      call remember()
      call forces(force)
      call kick(v)
      if (mod(step, stride) == 0) then
        sample = step / stride + 1
        t_out(sample) = step * dt
        g_out(:, sample) = gap
        ! the physical gaps: the series springs' displacements added
        if (series) g_out(:, sample) = gap + matmul(cmat, force)
        e_out(sample) = energy()
        if (.not. e_out(sample) <= energy_bound) status = &
            status_energy_bound
      end if
      if (mod(step, stop_check_every) == 0) then
        if (.not. energy() <= energy_bound) status = status_energy_bound
        if (stop_requested /= 0) status = status_interrupted
      end if
      if (status /= status_ok) exit
    end do
    if (status == status_ok .and. .not. energy() <= energy_bound) &
        status = status_energy_bound
    book(1) = damped_work + law_plastic_work(law, k)
    book(2) = energy() - 0.5_wp * sum(m * (v**2 + (p * q)**2))

  contains

    !> The law's memory of the current penetrations (with the series
    !> correction, Thornton's elements' own depths, undamped: those the
    !> elastic energy reads).
    subroutine remember()
      real(wp) :: f(k), depth(k), factor(k)
      integer :: j

      if (series .and. law%plastic) then
        factor = 1.0_wp
        call series_law_forces(k, law, factor, cmat, gap, f, depth)
        do j = 1, k
          if (depth(j) > 0.0_wp) call law_remember(law, j, depth(j))
        end do
        return
      end if
      do j = 1, k
        if (gap(j) < 0.0_wp) call law_remember(law, j, -gap(j))
      end do
    end subroutine remember

    pure subroutine forces(f)
      real(wp), intent(out) :: f(k)

      real(wp) :: depth(k)

      if (series .and. law%plastic) then
        call series_law_contact_forces(n, k, law, cmat, gap, ht, v, f, &
            depth)
      else if (series) then
        call series_contact_forces(n, k, law%stiffness, law%chi, cmat, &
            gap, ht, v, f, law%linear)
      else
        call contact_forces(n, k, law, gap, ht, v, f)
      end if
    end subroutine forces

    !> The undamped forces at the current gaps (the damping's part of a
    !> force is the rest).
    pure subroutine elastic_forces(f)
      real(wp), intent(out) :: f(k)
      real(wp) :: stiff(k), depth(k)
      integer :: j

      if (series .and. law%plastic) then
        stiff = 1.0_wp
        call series_law_forces(k, law, stiff, cmat, gap, f, depth)
      else if (series) then
        stiff = law%stiffness
        call series_forces(k, stiff, cmat, gap, f, law%linear)
      else
        do j = 1, k
          f(j) = law_elastic_force(law, j, -gap(j))
        end do
      end if
    end subroutine elastic_forces

    pure function gaps() result(g)
      real(wp) :: g(k)
      integer :: j

      do j = 1, k
        g(j) = dot_product(ht(:, j), q) + g0(j)
      end do
    end function gaps

    !> Half a step's kick of the forces; with damping, its work: the
    !> kick changes the kinetic energy by exactly sum_j J_j (u_j before
    !> + u_j after) / 2 (J_j = force_j dt / 2, u_j = h_j v), of which
    !> the damping's part J_j - J_j elastic is dissipated (also where
    !> the factor clips a penetrating contact's force to 0).
    subroutine kick(velocity)
      real(wp), intent(inout) :: velocity(n)
      real(wp) :: before(k), elastic(k)
      integer :: j

      if (law%chi /= 0.0_wp .and. any(gap < 0.0_wp)) then
        call elastic_forces(elastic)
        do j = 1, k
          before(j) = dot_product(ht(:, j), velocity)
        end do
      end if
      do j = 1, k
        if (force(j) /= 0.0_wp) velocity = velocity &
            + half_kick(:, j) * force(j)
      end do
      if (law%chi /= 0.0_wp .and. any(gap < 0.0_wp)) then
        do j = 1, k
          damped_work = damped_work - 0.25_wp * dt * (force(j) &
              - elastic(j)) * (before(j) + dot_product(ht(:, j), velocity))
        end do
      end if
    end subroutine kick

    pure function energy() result(total)
      real(wp) :: total, g(k)
      integer :: j

      g = gaps()
      if (series .and. law%plastic) then
        total = series_law_energy(k, law, cmat, g, &
            0.5_wp * sum(m * (v**2 + (p * q)**2)))
      else if (series) then
        total = 0.5_wp * sum(m * (v**2 + (p * q)**2)) &
            + series_energy(k, law%stiffness, cmat, g, law%linear)
      else
        total = 0.5_wp * sum(m * (v**2 + (p * q)**2))
        do j = 1, k
          total = total + law_energy(law, j, -g(j))
        end do
      end if
    end function energy

  end subroutine hertz

end module chatter_hertz
