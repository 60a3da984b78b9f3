#include <deal.II/base/exceptions.h>

#include <cycloid/profile/dxf_writer.h>

#include <fstream>
#include <iomanip>
#include <ostream>
#include <string>

namespace cycloid
{
  namespace profile
  {
    namespace
    {
      /** One DXF group: the code on one line, the value on the next. */
      template <typename T>
      void
      group(std::ostream &out, const int code, const T &value)
      {
        out << code << '\n' << value << '\n';
      }

      /** A point as groups 10/20/30 (z = 0: the disc plane). */
      void
      point(std::ostream &out, const dealii::Point<2> &p)
      {
        group(out, 10, p[0]);
        group(out, 20, p[1]);
        group(out, 30, 0.0);
      }

      /** HEADER: version, units mm, metric. */
      void
      header(std::ostream &out)
      {
        group(out, 0, "SECTION");
        group(out, 2, "HEADER");
        group(out, 9, "$ACADVER");
        group(out, 1, "AC1009");
        group(out, 9, "$INSUNITS");
        group(out, 70, 4);
        group(out, 9, "$MEASUREMENT");
        group(out, 70, 1);
        group(out, 0, "ENDSEC");
      }

      /** One LAYER table entry with colour @p colour. */
      void
      layer(std::ostream &out, const std::string &name, const int colour)
      {
        group(out, 0, "LAYER");
        group(out, 2, name);
        group(out, 70, 0);
        group(out, 62, colour);
        group(out, 6, "CONTINUOUS");
      }

      /** TABLES: the line type CONTINUOUS the layers refer to, and the
       * layers 0, PROFILE, HOLES. */
      void
      tables(std::ostream &out)
      {
        group(out, 0, "SECTION");
        group(out, 2, "TABLES");
        group(out, 0, "TABLE");
        group(out, 2, "LTYPE");
        group(out, 70, 1);
        group(out, 0, "LTYPE");
        group(out, 2, "CONTINUOUS");
        group(out, 70, 0);
        group(out, 3, "Solid line");
        group(out, 72, 65);
        group(out, 73, 0);
        group(out, 40, 0.0);
        group(out, 0, "ENDTAB");
        group(out, 0, "TABLE");
        group(out, 2, "LAYER");
        group(out, 70, 3);
        layer(out, "0", 7);
        layer(out, "PROFILE", 1);
        layer(out, "HOLES", 5);
        group(out, 0, "ENDTAB");
        group(out, 0, "ENDSEC");
      }

      /** The closed POLYLINE of the profile. */
      void
      polyline(std::ostream &out, const DiscOutline &outline)
      {
        group(out, 0, "POLYLINE");
        group(out, 8, "PROFILE");
        group(out, 66, 1); // vertices follow
        point(out, dealii::Point<2>());
        group(out, 70, 1); // closed
        for (const auto &v : outline.vertices)
          {
            group(out, 0, "VERTEX");
            group(out, 8, "PROFILE");
            point(out, v);
          }
        group(out, 0, "SEQEND");
        group(out, 8, "PROFILE");
      }
    } // namespace



    void
    write_dxf(const DiscOutline &outline, const std::string &filename)
    {
      std::ofstream out(filename);
      AssertThrow(out.good(),
                  dealii::ExcMessage("cannot write '" + filename +
                                     "' (check Output directory)."));
      out << std::setprecision(15);
      header(out);
      tables(out);
      group(out, 0, "SECTION");
      group(out, 2, "ENTITIES");
      polyline(out, outline);
      for (const auto &hole : outline.holes)
        {
          group(out, 0, "CIRCLE");
          group(out, 8, "HOLES");
          point(out, hole.centre);
          group(out, 40, hole.radius);
        }
      group(out, 0, "ENDSEC");
      group(out, 0, "EOF");
      out.close();
      AssertThrow(!out.fail(),
                  dealii::ExcMessage("writing '" + filename + "' failed."));
    }
  } // namespace profile
} // namespace cycloid
