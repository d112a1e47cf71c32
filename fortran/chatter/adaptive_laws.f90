!> The fixed steps of the adaptive stepper (chatter_adaptive), taken
!> where a contact may close, by its two contact laws: Hertz's forces in
!> the splitting of chatter_hertz (half kick, exact flow, half kick) and
!> Newton's impulses at the step's midpoint (the one-step LCP solved as
!> chatter_moreau_jean solves it).  Each records contact 1's first
!> episode and watches the crossings and the largest gap of its flows.
module chatter_adaptive_laws
  use contactsep_kinds, only: wp
  use chatter_lcp, only: solve_lcp
  use chatter_status, only: status_lcp_unsolved
  use chatter_adaptive_state, only: adaptive_run
  use chatter_adaptive_flow, only: flow
  use chatter_adaptive_crossings, only: watch_fixed, watch_grid
  use chatter_hertz_series, only: series_forces, series_law_forces
  use chatter_contact_law, only: law_force, law_elastic_force, &
      law_remember, max_contacts
  implicit none
  private
  public :: hertz_step, newton_step

contains

  !> A step of the fixed-step splitting from step `step`, as
  !> chatter_hertz takes it: half kick, exact flow, half kick.
  !> The start's forces are the last step's end forces where that step
  !> ended here and chi = 0 (the same call on the same gaps); the work
  !> arrays are fixed-size (k <= max_contacts): no heap traffic a step.
  subroutine hertz_step(run, step)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: step
    logical :: kicked
    real(wp) :: force_a(max_contacts), gap_a(max_contacts)
    real(wp) :: ga(max_contacts), gb(max_contacts)
    integer :: k

    k = run%k
    if (run%chi /= 0.0_wp .or. run%forces_at /= step) &
        call contact_forces(run)
    if (run%force(1) > 0.0_wp .and. run%episode == 0) then
      run%episode = 1
      run%first(1) = real(step, wp) * run%dt
      run%first(2) = 0.0_wp
    end if
    if (run%episode == 1) then
      if (run%force(1) > 0.0_wp) then
        run%first(2) = run%first(2) + run%force(1) * run%dt
      else
        run%episode = 2
      end if
    end if
    kicked = any(run%force /= 0.0_wp)
    call kick(run, step)
    call flow(run, 1)
    run%t_now = real(step + 1, wp) * run%dt
    if (run%series) then
      ! the end's forces first: where either end has one, the physical
      ! gaps are watched on the grid (watch_grid)
      force_a(1:k) = run%force
      gap_a(1:k) = run%gap
      run%gap(:) = run%gap_new
      call contact_forces(run)
      if (any(force_a(1:k) /= 0.0_wp) .or. any(run%force /= 0.0_wp)) then
        call physical_gaps(run, gap_a, force_a, ga)
        call physical_gaps(run, run%gap, run%force, gb)
        call watch_grid(run, ga, gb, run%t_now)
      else
        run%gap(:) = gap_a(1:k)
        call watch_fixed(run, run%dt, 1, run%t_now)
        run%gap(:) = run%gap_new
      end if
    else
      call watch_fixed(run, run%dt, 1, run%t_now)
      run%gap(:) = run%gap_new
      call contact_forces(run)
    end if
    run%forces_at = step + 1
    kicked = kicked .or. any(run%force /= 0.0_wp)
    call kick(run, step + 1)
    run%amp_fresh = run%amp_fresh .and. .not. kicked
    run%rate_fresh = .not. kicked
    if (run%rate_fresh) run%rate(:) = run%rate_new
    run%e_fresh = run%e_fresh .and. .not. kicked
  end subroutine hertz_step

  !> g + C lambda, the physical gaps of modal gaps g and forces lambda,
  !> summed as matmul sums C lambda.
  pure subroutine physical_gaps(run, g, force, physical)
    type(adaptive_run), intent(in) :: run
    real(wp), intent(in) :: g(run%k), force(run%k)
    real(wp), intent(out) :: physical(run%k)
    real(wp) :: row
    integer :: i, j

    do i = 1, run%k
      row = 0.0_wp
      do j = 1, run%k
        row = row + run%cmat(i, j) * force(j)
      end do
      physical(i) = g(i) + row
    end do
  end subroutine physical_gaps

  !> One Newton step from step `step`: flow dt/2, the impulses, flow
  !> dt/2.
  subroutine newton_step(run, step)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: step
    ! one or two contacts (with one, impulse(2) stays 0)
    real(wp) :: d(2, 2), b(2), z(2), noise, impulse(2), t_mid
    integer :: active(2), na, i, j
    logical :: ok, kicked

    call flow(run, -1)
    t_mid = (real(step, wp) + 0.5_wp) * run%dt
    call watch_fixed(run, 0.5_wp * run%dt, -1, t_mid)
    run%gap(:) = run%gap_new
    ! closed at the midpoint and not separating beyond the round-off
    ! of the rate (a resting contact has u = 0 +- that)
    na = 0
    do j = 1, run%k
      noise = 64.0_wp * epsilon(1.0_wp) * sum(abs(run%ht(:, j) * run%v))
      if (run%gap(j) <= 0.0_wp .and. run%rate_new(j) <= noise) then
        na = na + 1
        active(na) = j
      end if
    end do
    impulse = 0.0_wp
    if (na > 0) then
      do i = 1, na
        do j = 1, na
          d(i, j) = run%coupling(active(i), active(j))
        end do
        b(i) = (1.0_wp + run%restitution) * run%rate_new(active(i))
      end do
      call solve_lcp(na, d, b, z, ok)
      if (.not. ok) then
        run%status = status_lcp_unsolved
        return
      end if
      do i = 1, na
        impulse(active(i)) = z(i)
        if (z(i) /= 0.0_wp) call axpy(run%n, z(i), &
            run%inv_mh(:, active(i)), run%v)
      end do
    end if
    if (impulse(1) > 0.0_wp .and. run%episode == 0) then
      run%episode = 1
      run%first(1) = t_mid
      run%first(2) = 0.0_wp
    end if
    if (run%episode == 1) then
      if (impulse(1) > 0.0_wp) then
        run%first(2) = run%first(2) + impulse(1)
      else
        run%episode = 2
      end if
    end if
    kicked = any(impulse /= 0.0_wp)
    run%amp_fresh = run%amp_fresh .and. .not. kicked
    run%e_fresh = run%e_fresh .and. .not. kicked
    call flow(run, -1)
    call watch_fixed(run, 0.5_wp * run%dt, -1, real(step + 1, wp) &
        * run%dt)
    run%gap(:) = run%gap_new
    run%rate(:) = run%rate_new
    run%rate_fresh = .true.
  end subroutine newton_step

  !> F = F_e (1 + chi delta'), F >= 0, as chatter_hertz, of the
  !> current gaps, into run%force; the law remembers the penetrations
  !> (chatter_contact_law).
  subroutine contact_forces(run)
    type(adaptive_run), intent(inout) :: run
    real(wp) :: stiff(max_contacts), depth(max_contacts)
    integer :: j

    if (run%series .and. run%law%plastic) then
      ! Thornton's elements in series: their own (undamped) depths
      ! remembered, then the forces with Flores's factor
      if (all(run%gap >= 0.0_wp)) then
        run%force(:) = 0.0_wp
        return
      end if
      stiff(1:run%k) = 1.0_wp
      call series_law_forces(run%k, run%law, stiff(1:run%k), run%cmat, &
          run%gap, run%force, depth(1:run%k))
      do j = 1, run%k
        if (depth(j) > 0.0_wp) call law_remember(run%law, j, depth(j))
      end do
      if (run%chi == 0.0_wp) return
      do j = 1, run%k
        stiff(j) = max(1.0_wp - run%chi * rate(run, j), 0.0_wp)
      end do
      call series_law_forces(run%k, run%law, stiff(1:run%k), run%cmat, &
          run%gap, run%force, depth(1:run%k))
      return
    end if
    if (run%series) then
      ! the static correction (chatter_hertz_series), Flores's factor
      ! on each element's stiffness, as chatter_hertz
      if (all(run%gap >= 0.0_wp)) then
        run%force(:) = 0.0_wp
        return
      end if
      stiff(1:run%k) = run%stiffness
      if (run%chi /= 0.0_wp) then
        do j = 1, run%k
          stiff(j) = run%stiffness * max(1.0_wp - run%chi &
              * rate(run, j), 0.0_wp)
        end do
      end if
      call series_forces(run%k, stiff, run%cmat, run%gap, run%force, &
          run%law%linear)
      return
    end if
    do j = 1, run%k
      if (run%gap(j) < 0.0_wp) then
        call law_remember(run%law, j, -run%gap(j))
        run%force(j) = law_force(run%law, j, -run%gap(j), &
            rate(run, j))
      else
        run%force(j) = 0.0_wp
      end if
    end do
  end subroutine contact_forces

  !> The undamped forces at the current gaps (the damping's part of a
  !> force is the rest).
  subroutine elastic_forces(run, force)
    type(adaptive_run), intent(in) :: run
    real(wp), intent(out) :: force(run%k)
    real(wp) :: stiff(max_contacts), depth(max_contacts)
    integer :: j

    if (run%series .and. run%law%plastic) then
      stiff(1:run%k) = 1.0_wp
      call series_law_forces(run%k, run%law, stiff(1:run%k), run%cmat, &
          run%gap, force, depth(1:run%k))
    else if (run%series) then
      stiff(1:run%k) = run%stiffness
      call series_forces(run%k, stiff, run%cmat, run%gap, force, &
          run%law%linear)
    else
      do j = 1, run%k
        force(j) = law_elastic_force(run%law, j, -run%gap(j))
      end do
    end if
  end subroutine elastic_forces

  !> Half a step's kick of the Hertz forces in run%force; with damping,
  !> its work (as chatter_hertz's kick: the exact change of kinetic
  !> energy, its damping part) into run%damped_work.  `at`: the fixed
  !> step whose start the state is; the undamped forces depend on the
  !> gaps (and the law's memory, which the same gaps leave as it is)
  !> alone, so the end kick's serve the next step's start kick.
  subroutine kick(run, at)
    type(adaptive_run), intent(inout) :: run
    integer, intent(in) :: at
    real(wp) :: before(max_contacts), elastic(max_contacts)
    logical :: damped
    integer :: j

    damped = run%chi /= 0.0_wp .and. any(run%gap < 0.0_wp)
    if (damped) then
      if (run%elastic_at /= at) then
        call elastic_forces(run, elastic)
        run%elastic(1:run%k) = elastic(1:run%k)
        run%elastic_at = at
      end if
      do j = 1, run%k
        before(j) = rate(run, j)
      end do
    end if
    do j = 1, run%k
      if (run%force(j) /= 0.0_wp) call axpy(run%hi(j) - run%lo(j) + 1, &
          run%force(j), run%half_kick(run%lo(j):run%hi(j), j), &
          run%v(run%lo(j):run%hi(j)))
    end do
    if (damped) then
      do j = 1, run%k
        run%damped_work = run%damped_work - 0.25_wp * run%dt &
            * (run%force(j) - run%elastic(j)) * (before(j) &
            + rate(run, j))
      end do
    end if
  end subroutine kick

  !> The rate h_c v of contact c's gap, over the modes its Jacobian
  !> touches (the rest add only zeros), in dot_product's order.
  pure real(wp) function rate(run, c)
    type(adaptive_run), intent(in) :: run
    integer, intent(in) :: c

    rate = dot_product(run%ht(run%lo(c):run%hi(c), c), &
        run%v(run%lo(c):run%hi(c)))
  end function rate

  !> y += alpha x.
  pure subroutine axpy(nm, alpha, x, y)
    integer, intent(in) :: nm
    real(wp), intent(in) :: alpha, x(nm)
    real(wp), intent(inout) :: y(nm)

    y = y + alpha * x
  end subroutine axpy

end module chatter_adaptive_laws
