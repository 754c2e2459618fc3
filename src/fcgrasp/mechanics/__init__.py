r"""Contact mechanics of planar and of solid grasps, mirrored: ``planar`` and ``spatial``
have the same modules (``contacts``, ``closure``, ``quality``) with the same functions and
the same parameters, as pytransform3d mirrors its ``rotations`` and ``transformations``.

A grasp is its contacts' ``points`` (k, D) and the part's **outward** unit ``normals``
(k, D) there, D = 2 in the plane and 3 on a solid (the convention of every JSON report;
a finger pushes along ``-n``), with Coulomb friction ``mu`` per contact or one for all.
Solid contacts add ``torsion``, the soft finger's torsional friction length (a moment
about the normal has no planar counterpart), and ``facets``, the number of edges of the
pyramid that stands for the circular friction cone (a planar cone is two edges, exact).

Wrenches are ``(force, torque / radius)``, torques about ``center`` (default: the
contacts' mean) divided by ``radius`` (default: the largest distance of a contact from
``center``), so every measure is unit-free (Ferrari and Canny's ``lambda``):
``(fx, fy, tau)`` in the plane (paper eq. 3), ``(f, m)`` on a solid.

================================  ===============================================
``contacts.contact_wrenches``     each contact's wrench generators, unit normal force
``closure.force_closure``         the verdict (theorem 6.1 in the plane; the exact
                                  quadratic cones of a cone program on solids)
``closure.unresisted_wrench``     a unit wrench no contact force resists, or None
``quality.epsilon``               Ferrari-Canny's L1 epsilon (section 8.1)
``quality.volume``                the volume of the grasp wrench space
================================  ===============================================

>>> from fcgrasp.mechanics import planar, spatial
>>> planar.force_closure([[1, 0], [-1, 0]], [[1, 0], [-1, 0]], mu=0.3)
True
>>> spatial.force_closure([[1, 0, 0], [-1, 0, 0]], [[1, 0, 0], [-1, 0, 0]], mu=0.3,
...                       torsion=0.01)
True
"""

from . import planar, spatial

__all__ = ["planar", "spatial"]
