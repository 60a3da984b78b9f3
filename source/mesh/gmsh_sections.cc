#include <deal.II/base/exceptions.h>

#include <cycloid/mesh/gmsh_bodies.h>
#include <cycloid/mesh/gmsh_sections.h>
#include <cycloid/mesh/ids.h>
#include <cycloid/mesh/quad_split.h>
#include <cycloid/mesh/size_field.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>

#include <gmsh.h>

namespace cycloid
{
  namespace mesh
  {
    namespace internal
    {
      namespace
      {
        /**
         * gmsh's nodes numbered in the order the cells first use them, so
         * that the raw mesh holds only the nodes of its cells; a node's
         * coordinates are appended to the raw mesh when it is first met.
         */
        class NodeNumbering
        {
        public:
          /** All nodes of the current gmsh model, appended to @p raw. */
          explicit NodeNumbering(RawMesh &raw)
            : raw(raw)
          {
            std::vector<double> params;
            gmsh::model::mesh::getNodes(
              node_tags, coords, params, -1, -1, true, false);
            for (std::size_t i = 0; i < node_tags.size(); ++i)
              position[node_tags[i]] = i;
          }

          /** Index in the raw mesh of gmsh node @p n. */
          unsigned int
          operator()(const std::size_t n)
          {
            auto it = index.find(n);
            if (it == index.end())
              {
                const unsigned int v = raw.coordinates.size() / 3;
                it                   = index.emplace(n, v).first;
                const std::size_t p  = position.at(n);
                for (unsigned int c = 0; c < 3; ++c)
                  raw.coordinates.push_back(coords[3 * p + c]);
              }
            return it->second;
          }

        private:
          RawMesh                            &raw;
          std::vector<std::size_t>            node_tags;
          std::vector<double>                 coords;
          std::map<std::size_t, std::size_t>  position;
          std::map<std::size_t, unsigned int> index;
        };



        /** The 2D elements (triangles, quadrilaterals) of @p body, as node
         * indices of the raw mesh. */
        std::vector<std::vector<unsigned int>>
        elements_of(const Body &body, NodeNumbering &node)
        {
          std::vector<std::vector<unsigned int>> elements;
          bool                                   triangles = false;
          for (const int entity : body.surfaces)
            {
              std::vector<int>                      types;
              std::vector<std::vector<std::size_t>> tags, nodes;
              gmsh::model::mesh::getElements(types, tags, nodes, 2, entity);
              for (std::size_t t = 0; t < types.size(); ++t)
                {
                  AssertThrow(types[t] == 2 || types[t] == 3,
                              dealii::ExcMessage(
                                "gmsh produced elements of type " +
                                std::to_string(types[t]) + " in " +
                                ids::body_name(body.material) + "."));
                  const unsigned int nv = (types[t] == 2) ? 3 : 4;
                  triangles             = triangles || (nv == 3);
                  for (std::size_t e = 0; e < tags[t].size(); ++e)
                    {
                      std::vector<unsigned int> el;
                      for (unsigned int k = 0; k < nv; ++k)
                        el.push_back(node(nodes[t][nv * e + k]));
                      elements.push_back(el);
                    }
                }
            }
          // The housing is structured: a triangle there is a bug.
          AssertThrow(!triangles || body.material != ids::housing,
                      dealii::ExcInternalError());
          return elements;
        }



        /** The edges of the mesh on @p body's exact circles, as pairs of
         * raw-mesh node indices (smaller first). */
        std::set<std::pair<unsigned int, unsigned int>>
        edges_on_circles(const Body &body, NodeNumbering &node)
        {
          std::set<std::pair<unsigned int, unsigned int>> on_circle;
          for (const int curve : body.circles)
            {
              std::vector<int>                      types;
              std::vector<std::vector<std::size_t>> tags, nodes;
              gmsh::model::mesh::getElements(types, tags, nodes, 1, curve);
              for (std::size_t t = 0; t < types.size(); ++t)
                for (std::size_t e = 0; e + 1 < nodes[t].size(); e += 2)
                  on_circle.insert(
                    std::minmax(node(nodes[t][e]), node(nodes[t][e + 1])));
            }
          return on_circle;
        }



        /**
         * The cells of the meshed @p bodies: gmsh's elements, those of the
         * discs and pins split once into quadrilaterals with the midpoints
         * of their curved boundary edges on the exact circles (the flank is
         * projected after extrusion).
         */
        RawMesh
        extract_raw_mesh(const MeshSettings              &settings,
                         const geometry::CycloidGeometry &geometry,
                         const double                     psi,
                         const std::vector<Body>         &bodies)
        {
          RawMesh       raw;
          NodeNumbering node(raw);
          for (const Body &body : bodies)
            {
              std::vector<std::vector<unsigned int>> elements =
                elements_of(body, node);
              if (body.material != ids::housing)
                {
                  const auto on_circle = edges_on_circles(body, node);
                  elements             = split_into_quadrilaterals(
                    elements,
                    raw.coordinates,
                    circles_of(settings, geometry, psi, body.material),
                    on_circle);
                }
              for (const auto &el : elements)
                {
                  raw.cells.insert(raw.cells.end(), el.begin(), el.end());
                  raw.materials.push_back(body.material);
                }
            }
          return raw;
        }



        /** Physical groups, so that a written .msh keeps the bodies'
         * identification. */
        void
        add_physical_groups(const std::vector<Body> &bodies)
        {
          for (const Body &body : bodies)
            {
              const int tag = gmsh::model::addPhysicalGroup(2,
                                                            body.surfaces,
                                                            body.material + 1);
              gmsh::model::setPhysicalName(2,
                                           tag,
                                           ids::body_name(body.material));
            }
        }
      } // namespace



      RawMesh
      generate_sections(const MeshSettings              &settings,
                        const geometry::CycloidGeometry &geometry,
                        const double                     psi,
                        const std::string               &msh_file,
                        const double                     sweep)
      {
        gmsh::initialize(0, nullptr, false);
        gmsh::option::setNumber("General.Terminal",
                                std::getenv("CYCLOID_GMSH_VERBOSE") ? 1 : 0);
        gmsh::option::setNumber("General.NumThreads", 1);
        gmsh::model::add("cycloid-stage");

        PinEntities             pins;
        const std::vector<Body> bodies =
          add_bodies(settings, geometry, psi, pins);
        gmsh::model::geo::synchronize();

        const SizeField field(settings, geometry, psi, sweep, pins);
        set_size_field_and_options(field, bodies);
        add_physical_groups(bodies);

        // Blossom recombination gives quadrilaterals where the parity and
        // shape of a surface allow, but may leave a few triangles, and where
        // it does changes with the crank angle: the extraction splits every
        // element of the discs and pins (meshed at twice the size) once
        // into quadrilaterals.
        gmsh::model::mesh::generate(2);
        if (!msh_file.empty())
          gmsh::write(msh_file);

        RawMesh raw = extract_raw_mesh(settings, geometry, psi, bodies);
        gmsh::finalize();
        return raw;
      }
    } // namespace internal
  }   // namespace mesh
} // namespace cycloid
