#include <deal.II/base/numbers.h>

#include <cycloid/mesh/gmsh_bodies.h>
#include <cycloid/mesh/ids.h>

#include <algorithm>
#include <cmath>

#include <gmsh.h>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      namespace
      {
        namespace geo       = gmsh::model::geo;
        constexpr double pi = dealii::numbers::PI;

        /**
         * gmsh's geo-kernel circle through three 120-degree arcs (an arc
         * must span less than pi); its arcs are appended to @p curves.
         * Returns the curve loop.
         */
        int
        add_circle(const dealii::Point<2> &c,
                   const double            r,
                   const double            z,
                   const double            size,
                   std::vector<int>       &curves)
        {
          const int centre = geo::addPoint(c[0], c[1], z, size);
          int       p[3];
          for (unsigned int k = 0; k < 3; ++k)
            p[k] = geo::addPoint(c[0] + r * std::cos(2. * pi * k / 3.),
                                 c[1] + r * std::sin(2. * pi * k / 3.),
                                 z,
                                 size);
          std::vector<int> arcs;
          for (unsigned int k = 0; k < 3; ++k)
            arcs.push_back(geo::addCircleArc(p[k], centre, p[(k + 1) % 3]));
          curves.insert(curves.end(), arcs.begin(), arcs.end());
          return geo::addCurveLoop(arcs);
        }



        /**
         * Disc @p d placed at crank angle @p psi: the profile as one spline
         * per tooth, tip to tip (gmsh's splines follow the profile closely
         * enough for meshing; the vertices are projected onto the exact
         * profile later), the bore and the crank holes.
         */
        Body
        add_disc(const MeshSettings              &settings,
                 const geometry::CycloidGeometry &geometry,
                 const unsigned int               d,
                 const double                     psi)
        {
          const auto        &g           = settings.geometry;
          const double       lc          = settings.mesh.coarse_size;
          const unsigned int zc          = g.n_teeth;
          const unsigned int n_per_tooth = 24;
          const auto        &profile     = geometry.disc_profile(d);
          const double       z0 = 0.; // sections at z = 0, extruded later
          std::vector<int>   tips(zc);
          for (unsigned int k = 0; k < zc; ++k)
            {
              const auto p =
                geometry.to_housing(d,
                                    psi,
                                    profile.profile(2. * pi * k - pi).point);
              tips[k] = geo::addPoint(p[0], p[1], z0, lc);
            }
          std::vector<int> teeth;
          for (unsigned int k = 0; k < zc; ++k)
            {
              std::vector<int> pts{tips[k]};
              for (unsigned int i = 1; i < n_per_tooth; ++i)
                {
                  const double phi =
                    2. * pi * k - pi + 2. * pi * i / n_per_tooth;
                  const auto p =
                    geometry.to_housing(d, psi, profile.profile(phi).point);
                  pts.push_back(geo::addPoint(p[0], p[1], z0, lc));
                }
              pts.push_back(tips[(k + 1) % zc]);
              teeth.push_back(geo::addSpline(pts));
            }
          std::vector<int> loops{geo::addCurveLoop(teeth)};
          std::vector<int> curves;
          const auto       centre = geometry.disc_centre(d, psi);
          loops.push_back(add_circle(centre, g.bore_radius, z0, lc, curves));
          for (unsigned int k = 0; k < g.n_crank_holes; ++k)
            {
              const auto h = geometry.crank_hole_centre(d, k, psi);
              loops.push_back(
                add_circle(h, g.crank_hole_radius, z0, lc, curves));
            }
          Body body;
          body.material = ids::disc(d);
          body.surfaces = {geo::addPlaneSurface(loops)};
          body.circles  = curves;
          return body;
        }



        /**
         * Pin @p j: a core disc (held for Pin support = axis, so it is a
         * surface of its own) and the ring around it.
         */
        Body
        add_pin(const MeshSettings              &settings,
                const geometry::CycloidGeometry &geometry,
                const unsigned int               j,
                PinEntities                     &pins)
        {
          const double     lc = settings.mesh.coarse_size;
          std::vector<int> curves;
          const auto       c = geometry.pin_centre(j);
          const int        outer =
            add_circle(c, geometry.pin_radius(j), 0., lc, curves);
          const int core =
            add_circle(c, settings.scene.pin_core_radius, 0., lc, curves);
          Body body;
          body.material = ids::pin(j);
          body.surfaces = {geo::addPlaneSurface({outer, core}),
                           geo::addPlaneSurface({core})};
          for (const int curve : curves)
            pins.entities.emplace(1, curve);
          // The core circle: 3 arcs of 4 segments (24 edges after the
          // split), so that its curvature is resolved.
          for (std::size_t k = 3; k < curves.size(); ++k)
            geo::mesh::setTransfiniteCurve(curves[k], 5);
          for (const int s : body.surfaces)
            pins.entities.emplace(2, s);
          pins.core_surfaces.insert(body.surfaces[1]);
          body.circles = curves;
          return body;
        }



        /** Odd node count (an even number of segments, at least 2) for a
         * curve of @p length with segments of about @p h: the housing's
         * transfinite curves, so that the sectors close structurally. */
        int
        even_nodes(const double length, const double h)
        {
          const int n =
            std::max(2, 2 * static_cast<int>(std::ceil(0.5 * length / h)));
          return n + 1;
        }



        /** What the housing's sectors share: the ring's dimensions, the
         * radial lines between the sectors, and the transfinite constraints
         * and corners the sectors collect (set once all curves exist). */
        struct HousingFrame
        {
          /** Pin circle radius [mm]. */
          double rp;
          /** Half the angle a groove spans on the pin circle [rad]. */
          double half;
          /** Pin pitch [rad]. */
          double pitch;
          /** gmsh point at the stage axis (centre of the ring's arcs). */
          int origin;
          /** Per sector border j: inner and outer point, radial line. */
          std::vector<int> inner_pt, outer_pt, radial;
          /** (curve, number of nodes) of the transfinite curves. */
          std::vector<std::pair<int, int>> transfinite;
          /** Corner points of each sector. */
          std::vector<std::vector<int>> corners;
        };



        /**
         * Where the circle of centre @p c and radius @p r (a pin's groove)
         * crosses the circle of radius @p rp about the stage axis: the
         * point before (clockwise of) the pin, then the one after. For a
         * nominal pin this is rp (cos(a -+ half), sin(a -+ half)).
         */
        std::pair<dealii::Point<2>, dealii::Point<2>>
        groove_ends(const dealii::Point<2> &c, const double r, const double rp)
        {
          const double d = c.norm();
          // Along c from the axis, then across it.
          const double along           = (d * d + rp * rp - r * r) / (2. * d);
          const double across          = std::sqrt(rp * rp - along * along);
          const dealii::Tensor<1, 2> u = c / d;
          const dealii::Tensor<1, 2> t({-u[1], u[0]});
          return {dealii::Point<2>(along * u - across * t),
                  dealii::Point<2>(along * u + across * t)};
        }



        /**
         * The housing's sector of pin @p j, from the radial line half a
         * pitch before the pin to the one half a pitch after it: the inner
         * side (land, the groove split at its outermost point, land) and
         * the outer arc get the same number of segments, so that the sector
         * meshes as a structured (transfinite) quadrilateral.
         */
        void
        add_housing_sector(const MeshSettings              &settings,
                           const geometry::CycloidGeometry &geometry,
                           const unsigned int               j,
                           HousingFrame                    &frame,
                           Body                            &body)
        {
          const auto        &g    = settings.geometry;
          const auto        &m    = settings.mesh;
          const double       lc   = m.coarse_size;
          const double       rp   = frame.rp;
          const double       half = frame.half;
          const unsigned int next = (j + 1) % g.n_pins;
          // The groove is pin j's circle as the layout has it (a pin moved
          // or thicker than drawn sits in a seat that fits it); its ends are
          // where that circle crosses the nominal pin circle, the housing's
          // inner side, so that both arcs meeting there are exact.
          const double a = frame.pitch * j;
          const auto   c = geometry.pin_centre(j);
          const double r = geometry.pin_radius(j);
          // A nominal pin keeps the expressions its mesh was always built
          // with (the same mesh to the last bit without deviations).
          const bool nominal =
            c == dealii::Point<2>(rp * std::cos(2. * pi * j / g.n_pins),
                                  rp * std::sin(2. * pi * j / g.n_pins)) &&
            r == g.pin_radius;
          const auto ends =
            nominal ?
              std::make_pair(dealii::Point<2>(rp * std::cos(a - half),
                                              rp * std::sin(a - half)),
                             dealii::Point<2>(rp * std::cos(a + half),
                                              rp * std::sin(a + half))) :
              groove_ends(c, r, rp);
          const int centre = geo::addPoint(c[0], c[1], 0, lc);
          const int before = geo::addPoint(ends.first[0], ends.first[1], 0, lc);
          const int top    = geo::addPoint(c[0] + r * std::cos(a),
                                        c[1] + r * std::sin(a),
                                        0,
                                        lc);
          const int after =
            geo::addPoint(ends.second[0], ends.second[1], 0, lc);
          const int arc0 =
            geo::addCircleArc(frame.inner_pt[j], frame.origin, before);
          const int groove0 = geo::addCircleArc(before, centre, top);
          const int groove1 = geo::addCircleArc(top, centre, after);
          const int arc1 =
            geo::addCircleArc(after, frame.origin, frame.inner_pt[next]);
          const int    outer         = geo::addCircleArc(frame.outer_pt[next],
                                              frame.origin,
                                              frame.outer_pt[j]);
          const double land          = rp * (0.5 * frame.pitch - half);
          const double groove_length = r * (0.5 * pi + 0.5 * half);
          auto        &transfinite   = frame.transfinite;
          transfinite.emplace_back(arc0, even_nodes(land, m.pin_size));
          transfinite.emplace_back(arc1, even_nodes(land, m.pin_size));
          transfinite.emplace_back(groove0,
                                   even_nodes(groove_length, m.pin_size));
          transfinite.emplace_back(groove1,
                                   even_nodes(groove_length, m.pin_size));
          int inner_segments = 0;
          for (std::size_t k = transfinite.size() - 4; k < transfinite.size();
               ++k)
            inner_segments += transfinite[k].second - 1;
          transfinite.emplace_back(outer, inner_segments + 1);
          body.circles.insert(body.circles.end(),
                              {arc0, groove0, groove1, arc1, outer});
          const int loop = geo::addCurveLoop({arc0,
                                              groove0,
                                              groove1,
                                              arc1,
                                              frame.radial[next],
                                              outer,
                                              -frame.radial[j]});
          body.surfaces.push_back(geo::addPlaneSurface({loop}));
          frame.corners.push_back({frame.inner_pt[j],
                                   frame.inner_pt[next],
                                   frame.outer_pt[next],
                                   frame.outer_pt[j]});
        }



        /**
         * Housing ring rp ... rp + t with a groove of radius rrp per pin,
         * built from zp structured (transfinite) sectors, one per pin,
         * bounded by radial lines half a pin pitch away: quadrilaterals by
         * construction. Each groove is split at its outermost point so that
         * every arc spans less than pi.
         */
        Body
        add_housing(const MeshSettings              &settings,
                    const geometry::CycloidGeometry &geometry)
        {
          const auto        &g       = settings.geometry;
          const auto        &m       = settings.mesh;
          const double       lc      = m.coarse_size;
          const unsigned int zp      = g.n_pins;
          const double       rp      = geometry.pin_circle_radius();
          const double       outer_r = rp + g.housing_thickness;
          HousingFrame       frame;
          frame.rp = rp;
          frame.half =
            std::acos(1. - g.pin_radius * g.pin_radius / (2. * rp * rp));
          frame.pitch  = 2. * pi / zp;
          frame.origin = geo::addPoint(0, 0, 0, lc);
          frame.inner_pt.resize(zp);
          frame.outer_pt.resize(zp);
          frame.radial.resize(zp);
          for (unsigned int j = 0; j < zp; ++j)
            {
              const double t = frame.pitch * j - 0.5 * frame.pitch;
              frame.inner_pt[j] =
                geo::addPoint(rp * std::cos(t), rp * std::sin(t), 0, lc);
              frame.outer_pt[j] = geo::addPoint(outer_r * std::cos(t),
                                                outer_r * std::sin(t),
                                                0,
                                                lc);
              frame.radial[j] =
                geo::addLine(frame.inner_pt[j], frame.outer_pt[j]);
            }
          // Radial lines graded from the seat (about pin size) outwards.
          const double ratio    = 1.25;
          int          n_radial = 1; // nodes = segments + 1
          for (double covered = 0, h = m.pin_size;
               covered < g.housing_thickness;
               h = std::min(h * ratio, m.coarse_size))
            {
              covered += h;
              ++n_radial;
            }
          Body body;
          body.material = ids::housing;
          for (unsigned int j = 0; j < zp; ++j)
            add_housing_sector(settings, geometry, j, frame, body);
          // geo-kernel constraints: they survive geo::synchronize().
          for (const auto &[curve, n] : frame.transfinite)
            geo::mesh::setTransfiniteCurve(curve, n);
          for (unsigned int j = 0; j < zp; ++j)
            geo::mesh::setTransfiniteCurve(frame.radial[j],
                                           n_radial,
                                           "Progression",
                                           ratio);
          for (std::size_t k = 0; k < body.surfaces.size(); ++k)
            {
              geo::mesh::setTransfiniteSurface(body.surfaces[k],
                                               "Left",
                                               frame.corners[k]);
              geo::mesh::setRecombine(2, body.surfaces[k]);
            }
          return body;
        }
      } // namespace



      std::vector<Body>
      add_bodies(const MeshSettings              &settings,
                 const geometry::CycloidGeometry &geometry,
                 const double                     psi,
                 PinEntities                     &pins)
      {
        std::vector<Body> bodies;
        for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
          bodies.push_back(add_disc(settings, geometry, d, psi));
        for (unsigned int j = 0; j < settings.geometry.n_pins; ++j)
          bodies.push_back(add_pin(settings, geometry, j, pins));
        if (settings.scene.pin_support ==
            parameters::SceneParameters::PinSupport::housing)
          bodies.push_back(add_housing(settings, geometry));
        return bodies;
      }



      std::vector<Circle>
      circles_of(const MeshSettings              &settings,
                 const geometry::CycloidGeometry &geometry,
                 const double                     psi,
                 const dealii::types::material_id m)
      {
        const auto         &g  = settings.geometry;
        const double        rp = geometry.pin_circle_radius();
        std::vector<Circle> circles;
        if (ids::is_pin(m))
          {
            const unsigned int j = ids::pin_index(m);
            const auto         c = geometry.pin_centre(j);
            circles              = {{c, geometry.pin_radius(j)},
                                    {c, settings.scene.pin_core_radius}};
          }
        else if (ids::is_disc(m))
          {
            circles.push_back({geometry.disc_centre(m, psi), g.bore_radius});
            for (unsigned int k = 0; k < g.n_crank_holes; ++k)
              circles.push_back(
                {geometry.crank_hole_centre(m, k, psi), g.crank_hole_radius});
          }
        else
          {
            circles = {{dealii::Point<2>(), rp},
                       {dealii::Point<2>(), rp + g.housing_thickness}};
            for (unsigned int j = 0; j < g.n_pins; ++j)
              circles.push_back(
                {geometry.pin_centre(j), geometry.pin_radius(j)});
          }
        return circles;
      }
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid
