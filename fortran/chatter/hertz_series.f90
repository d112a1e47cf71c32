!> Hertz contacts in series with the residual flexibility of the
!> truncated modes (the static correction, docs/static-correction.md).
!>
!> The gaps of the modal contact points are g = H q + g0; the contact
!> forces lambda >= 0 add the quasi-static displacements C lambda of the
!> modes left out (C = [[c1 + c2, -c2], [-c2, c2 + c3]], c_i member i's
!> residual flexibility at its contact point), and each Hertz element
!> carries lambda_i = s_i delta_i^{3/2} on its own penetration
!> delta = -(g + C lambda) (s_i = k, times Flores's factor when damped).
!> lambda is the unique minimiser over lambda >= 0 of the convex
!>   Phi = sum_i (3/5) s_i^{-2/3} lambda_i^{5/3} + lambda^T C lambda / 2
!>         + lambda^T g,
!> and the elastic energy of the contacts is
!>   V(g) = -min Phi = sum_i (2/5) k delta_i^{5/2} + lambda^T C lambda / 2
!> with dV/dg = -lambda: the forces derive from V, so the splitting stays
!> symplectic.  lambda = 0 exactly when every g_i >= 0 (the gradient of
!> Phi at 0 is g), so no force acts while every modal gap is open.
!> Thornton's plastic law (law%plastic) takes the same series solve with
!> its own force F_e(delta) of the element's depth and memory in place
!> of k delta^{3/2} (series_law_forces): each element's root of
!> delta + c_ii s F_e(delta) = a (F_e increasing on the loading and the
!> unloading branch) by a bracketed Newton iteration (law_depth); the
!> caller remembers the elements' depths (law_remember), and the elastic
!> energy is sum_i law_energy(delta_i) + lambda^T C lambda / 2
!> (series_law_energy).
!> Twin: contactsep/chatter/contacts.py (series_forces, series_energy,
!> series_law_forces, series_law_energy).
module chatter_hertz_series
  use contactsep_kinds, only: wp
  use chatter_contact_law, only: max_contacts, contact_law, &
      law_elastic_force, law_elastic_slope, law_energy
  implicit none
  private
  public :: series_forces, series_energy, element_depth, max_sweeps
  public :: law_depth, series_law_forces, series_law_energy

  !> Most sweeps of the coordinate descent (it contracts by about
  !> c2^2 / ((c1 + c2)(c2 + c3)) a sweep: a few sweeps in practice).
  integer, parameter :: max_sweeps = 200
  !> Most Newton iterations of one element (quadratic from the first).
  integer, parameter :: max_newton = 100

contains

  !> The approach a_i = -g_i - sum_{j /= i} C_ij lambda_j that element i
  !> takes up with the other elements' forces as they stand: one step of
  !> the coordinate descent of every series solve (series_forces,
  !> series_law_forces), summed in j's order.
  pure function element_approach(k, i, cmat, g, force) result(a)
    integer, intent(in) :: k, i
    real(wp), intent(in) :: cmat(k, k), g(k), force(k)
    real(wp) :: a
    integer :: j

    a = -g(i)
    do j = 1, k
      if (j /= i) a = a - cmat(i, j) * force(j)
    end do
  end function element_approach

  !> Whether a sweep of the coordinate descent is the last: one contact
  !> is solved exactly by its one root; two are settled when the sweep
  !> moved no force by more than 4 ulps of it.
  pure function settled(k, force, old) result(done)
    integer, intent(in) :: k
    real(wp), intent(in) :: force(k), old(k)
    logical :: done

    done = k == 1
    if (.not. done) done = all(abs(force - old) <= 4.0_wp * epsilon(1.0_wp) &
        * force)
  end function settled

  !> The root delta >= 0 of delta + b delta^{3/2} = a (a > 0, b >= 0):
  !> Newton's method from the upper bound min(a, (a/b)^{2/3}); the
  !> function is convex and increasing, so the iterates fall
  !> monotonically onto the root, and stop when they stop falling.
  pure function element_depth(a, b) result(depth)
    real(wp), intent(in) :: a, b
    real(wp) :: depth, root, next
    integer :: it

    if (b <= 0.0_wp) then
      depth = a
      return
    end if
    ! (a/b)^{2/3} / a = (a b^2)^{-1/3} >= 1.26 where a b^2 <= 1/2: the
    ! bound is a there, and the pow (the dearest part of a step) spared
    if (a * b * b <= 0.5_wp) then
      depth = a
    else
      depth = min(a, (a / b)**(2.0_wp / 3.0_wp))
    end if
    do it = 1, max_newton
      root = sqrt(depth)
      next = depth - (depth + b * depth * root - a) &
          / (1.0_wp + 1.5_wp * b * root)
      if (.not. next < depth) exit
      depth = max(next, 0.0_wp)
    end do
  end function element_depth

  !> The forces lambda (lb) of k contacts (1 or 2) with Hertz
  !> stiffnesses stiff (lb/in^1.5; 0: no force), series flexibilities
  !> cmat (in/lb, symmetric positive semi-definite, diagonal >= 0) and
  !> modal gaps g (in): exact minimisation of Phi over each lambda_i in
  !> turn (coordinate descent; each step the root of one element) until
  !> a sweep changes no force by more than 4 ulps.
  !> With ``linear`` the elements are linear springs (F = s delta, a
  !> cylindrical button): each root is a / (1 + c_ii s).
  !> An element whose a is the same bits as at its last root keeps that
  !> root's force (the same call gives the same bits): a sweep after the
  !> first solves only the elements the other's force moved.
  pure subroutine series_forces(k, stiff, cmat, g, force, linear)
    integer, intent(in) :: k
    real(wp), intent(in) :: stiff(k), cmat(k, k), g(k)
    real(wp), intent(out) :: force(k)
    logical, intent(in), optional :: linear
    ! fixed size (k <= max_contacts): no heap traffic in a step
    real(wp) :: a, depth, old(max_contacts), solved(max_contacts)
    integer :: sweep, i
    logical :: line

    line = .false.
    if (present(linear)) line = linear

    force = 0.0_wp
    if (all(g >= 0.0_wp)) return
    ! a > 0 wherever a root is taken: 0 matches none
    solved = 0.0_wp
    do sweep = 1, max_sweeps
      old(1:k) = force
      do i = 1, k
        a = element_approach(k, i, cmat, g, force)
        if (a > 0.0_wp .and. stiff(i) > 0.0_wp .and. line) then
          force(i) = stiff(i) * a / (1.0_wp + cmat(i, i) * stiff(i))
        else if (a > 0.0_wp .and. stiff(i) > 0.0_wp) then
          if (a /= solved(i)) then
            depth = element_depth(a, cmat(i, i) * stiff(i))
            force(i) = stiff(i) * depth * sqrt(depth)
            solved(i) = a
          end if
        else
          force(i) = 0.0_wp
          solved(i) = 0.0_wp
        end if
      end do
      if (settled(k, force, old(1:k))) exit
    end do
  end subroutine series_forces

  !> V(g): the contacts' elastic energy (in lb), the Hertz elements'
  !> (2/5) k delta^{5/2} = (2/5) lambda delta and the series springs'
  !> lambda^T C lambda / 2, with the undamped forces of the gaps g.
  !> With ``linear``: linear elements, (1/2) lambda delta each.
  pure function series_energy(k, stiffness, cmat, g, linear) result(total)
    integer, intent(in) :: k
    real(wp), intent(in) :: stiffness, cmat(k, k), g(k)
    logical, intent(in), optional :: linear
    real(wp) :: total, force(max_contacts), stiff(max_contacts), depth
    real(wp) :: row
    integer :: i, j

    ! every gap open: no force, no energy (the sums below give +0 too)
    total = 0.0_wp
    if (all(g >= 0.0_wp)) return
    stiff(1:k) = stiffness
    call series_forces(k, stiff, cmat, g, force, linear)
    ! lambda^T C lambda, summed in matmul's and dot_product's order
    do i = 1, k
      row = 0.0_wp
      do j = 1, k
        row = row + cmat(i, j) * force(j)
      end do
      total = total + force(i) * row
    end do
    total = 0.5_wp * total
    if (present(linear)) then
      if (linear) then
        total = total + 0.5_wp * sum(force(1:k)**2) / stiffness
        return
      end if
    end if
    do i = 1, k
      if (force(i) > 0.0_wp) then
        depth = (force(i) / stiffness)**(2.0_wp / 3.0_wp)
        total = total + 0.4_wp * force(i) * depth
      end if
    end do
  end function series_energy

  !> The root delta in [0, a] of delta + b F_e(delta) = a (a > 0,
  !> b >= 0), F_e the elastic force of contact c with the law's memory
  !> (continuous and increasing): Newton's method from a, kept inside
  !> the bracket [lo, hi] of the root (a bisection where a step leaves
  !> it), until a step moves nothing or the bracket has no float left
  !> inside.  A b F_e(a) below a's last bit leaves a itself.
  pure function law_depth(law, c, a, b) result(depth)
    type(contact_law), intent(in) :: law
    integer, intent(in) :: c
    real(wp), intent(in) :: a, b
    real(wp) :: depth, lo, hi, f, next
    integer :: it

    depth = a
    if (b <= 0.0_wp) return
    lo = 0.0_wp
    hi = a
    do it = 1, 4 * max_newton
      f = depth + b * law_elastic_force(law, c, depth) - a
      if (f == 0.0_wp) exit
      if (f > 0.0_wp) then
        hi = depth
      else
        lo = depth
      end if
      next = depth - f / (1.0_wp + b * law_elastic_slope(law, c, depth))
      if (next == depth) exit
      if (.not. (next > lo .and. next < hi)) next = 0.5_wp * (lo + hi)
      if (next == lo .or. next == hi) exit
      depth = next
    end do
  end function law_depth

  !> series_forces for Thornton's law: the elements' forces
  !> factor_i F_e(delta_i) (factor: Flores's max(1 - chi u, 0), 1
  !> undamped) and depths delta_i (in; 0 where no force acts), F_e of
  !> each contact's memory as it stands (law_remember them after).
  pure subroutine series_law_forces(k, law, factor, cmat, g, force, depth)
    integer, intent(in) :: k
    type(contact_law), intent(in) :: law
    real(wp), intent(in) :: factor(k), cmat(k, k), g(k)
    real(wp), intent(out) :: force(k), depth(k)
    real(wp) :: a, old(max_contacts), solved(max_contacts)
    integer :: sweep, i

    force = 0.0_wp
    depth = 0.0_wp
    if (all(g >= 0.0_wp)) return
    solved = 0.0_wp
    do sweep = 1, max_sweeps
      old(1:k) = force
      do i = 1, k
        a = element_approach(k, i, cmat, g, force)
        if (a > 0.0_wp .and. factor(i) > 0.0_wp) then
          if (a /= solved(i)) then
            depth(i) = law_depth(law, i, a, cmat(i, i) * factor(i))
            force(i) = factor(i) * law_elastic_force(law, i, depth(i))
            solved(i) = a
          end if
        else
          ! no force: the element takes the whole approach
          force(i) = 0.0_wp
          depth(i) = max(a, 0.0_wp)
          solved(i) = 0.0_wp
        end if
      end do
      if (settled(k, force, old(1:k))) exit
    end do
  end subroutine series_law_forces

  !> base + series_energy for Thornton's law: base (the modal energy)
  !> + sum_i law_energy(delta_i) (the work each element's unloading
  !> curve gives back) + lambda^T C lambda / 2, summed in that order (as
  !> the plain law sums base and its contacts'), with the undamped
  !> forces of the gaps g and the memory as it stands.
  pure function series_law_energy(k, law, cmat, g, base) result(total)
    integer, intent(in) :: k
    type(contact_law), intent(in) :: law
    real(wp), intent(in) :: cmat(k, k), g(k), base
    real(wp) :: total, force(max_contacts), depth(max_contacts)
    real(wp) :: factor(max_contacts), row, springs
    integer :: i, j

    total = base
    if (all(g >= 0.0_wp)) return
    factor(1:k) = 1.0_wp
    call series_law_forces(k, law, factor(1:k), cmat, g, force(1:k), &
        depth(1:k))
    springs = 0.0_wp
    do i = 1, k
      row = 0.0_wp
      do j = 1, k
        row = row + cmat(i, j) * force(j)
      end do
      springs = springs + force(i) * row
    end do
    do i = 1, k
      total = total + law_energy(law, i, depth(i))
    end do
    total = total + 0.5_wp * springs
  end function series_law_energy

end module chatter_hertz_series
