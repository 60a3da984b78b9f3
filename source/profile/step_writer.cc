#include <deal.II/base/exceptions.h>

#include <deal.II/base/numbers.h>

#include <cycloid/profile/step_writer.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <Geom_BSplineCurve.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>

namespace cycloid
{
  namespace profile
  {
    namespace
    {
      /** The exact profile at spline parameter @p t = -phi, in 3D. */
      gp_Pnt
      exact(const geometry::CycloidGeometry &geometry, const double t)
      {
        const dealii::Point<2> p = geometry.profile(-t).point;
        return gp_Pnt(p[0], p[1], 0.);
      }

      /** The periodic cubic spline through the exact points at the
       * parameters @p t (period @p period). */
      Handle(Geom_BSplineCurve)
        interpolate(const geometry::CycloidGeometry &geometry,
                    const std::vector<double>       &t,
                    const double                     period)
      {
        const int n                        = t.size();
        Handle(TColgp_HArray1OfPnt) points = new TColgp_HArray1OfPnt(1, n);
        // A periodic interpolation takes one parameter more: the period's
        // end, where the curve returns to the first point.
        Handle(TColStd_HArray1OfReal) params =
          new TColStd_HArray1OfReal(1, n + 1);
        for (int i = 0; i < n; ++i)
          {
            points->SetValue(i + 1, exact(geometry, t[i]));
            params->SetValue(i + 1, t[i]);
          }
        params->SetValue(n + 1, period);
        GeomAPI_Interpolate interpolation(points, params, true, 1e-12);
        interpolation.Perform();
        AssertThrow(interpolation.IsDone(),
                    dealii::ExcMessage("OpenCASCADE could not interpolate the "
                                       "profile spline."));
        return interpolation.Curve();
      }

      /** Largest |spline - exact| at @p n_samples interior points of
       * spline interval @p i. */
      double
      interval_deviation(const geometry::CycloidGeometry &geometry,
                         const Handle(Geom_BSplineCurve) & spline,
                         const std::vector<double> &t,
                         const double               period,
                         const unsigned int         i,
                         const unsigned int         n_samples)
      {
        const double a     = t[i];
        const double b     = (i + 1 < t.size()) ? t[i + 1] : period;
        double       worst = 0;
        for (unsigned int k = 1; k <= n_samples; ++k)
          {
            const double s = a + (b - a) * k / (n_samples + 1.);
            worst =
              std::max(worst, spline->Value(s).Distance(exact(geometry, s)));
          }
        return worst;
      }

      /** The spline refined until every interval keeps within half of
       * @p tolerance at its quarter points. */
      Handle(Geom_BSplineCurve)
        refined_spline(const geometry::CycloidGeometry &geometry,
                       const double                     tolerance,
                       std::vector<double>             &t)
      {
        const unsigned int zc     = geometry.parameters().n_teeth;
        const double       period = 2. * dealii::numbers::PI * zc;
        for (unsigned int i = 0; i < 8 * zc; ++i)
          t.push_back(period * i / (8. * zc));
        for (unsigned int pass = 0; pass < 30; ++pass)
          {
            const Handle(Geom_BSplineCurve) spline =
              interpolate(geometry, t, period);
            std::vector<double> refined;
            refined.reserve(2 * t.size());
            for (unsigned int i = 0; i < t.size(); ++i)
              {
                refined.push_back(t[i]);
                if (interval_deviation(geometry, spline, t, period, i, 3) >
                    0.5 * tolerance)
                  refined.push_back(
                    0.5 * (t[i] + (i + 1 < t.size() ? t[i + 1] : period)));
              }
            if (refined.size() == t.size())
              return spline;
            t.swap(refined);
          }
        AssertThrow(false,
                    dealii::ExcMessage(
                      "the STEP spline did not meet "
                      "Profile/Chord tolerance in 30 passes."));
        return {};
      }

      /** A circle of the disc as a wire in z = 0. */
      TopoDS_Wire
      circle_wire(const Circle &c)
      {
        const gp_Circ circle(gp_Ax2(gp_Pnt(c.centre[0], c.centre[1], 0.),
                                    gp_Dir(0., 0., 1.)),
                             c.radius);
        return BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle));
      }

      /** The planar face: the spline as outer wire, the holes inside. */
      TopoDS_Face
      disc_face(const Handle(Geom_BSplineCurve) & spline,
                const std::vector<Circle> &holes)
      {
        const TopoDS_Wire outer =
          BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(spline));
        BRepBuilderAPI_MakeFace maker(gp_Pln(gp_Pnt(0., 0., 0.),
                                             gp_Dir(0., 0., 1.)),
                                      outer);
        // Inner wires run clockwise (against the face normal).
        for (const Circle &hole : holes)
          maker.Add(TopoDS::Wire(circle_wire(hole).Reversed()));
        AssertThrow(maker.IsDone(),
                    dealii::ExcMessage("OpenCASCADE could not build the disc "
                                       "face of the profile."));
        const TopoDS_Face face = maker.Face();
        AssertThrow(BRepCheck_Analyzer(face).IsValid(),
                    dealii::ExcMessage("OpenCASCADE finds the disc face of "
                                       "the profile invalid."));
        return face;
      }



      /** Write @p face to @p filename; OpenCASCADE's transfer statistics
       * are kept off the console for the call (they would bury the run's
       * summary), and no parameter-space curves are written (the face is
       * planar; they would double the file). */
      void
      write_face(const TopoDS_Face &face, const std::string &filename)
      {
        STEPControl_Writer writer; // initialises the write.step.* settings
        Interface_Static::SetCVal("write.step.unit", "MM");
        Interface_Static::SetCVal("write.step.schema", "AP214IS");
        Interface_Static::SetIVal("write.surfacecurve.mode", 0);
        std::vector<std::pair<Handle(Message_Printer), Message_Gravity>> quiet;
        for (const auto &printer : Message::DefaultMessenger()->Printers())
          {
            quiet.emplace_back(printer, printer->GetTraceLevel());
            printer->SetTraceLevel(Message_Fail);
          }
        writer.Transfer(face, STEPControl_AsIs);
        const IFSelect_ReturnStatus status = writer.Write(filename.c_str());
        for (const auto &[printer, level] : quiet)
          printer->SetTraceLevel(level);
        AssertThrow(status == IFSelect_RetDone,
                    dealii::ExcMessage("cannot write '" + filename +
                                       "' (check Output directory)."));
      }
    } // namespace



    StepSummary
    write_step(const geometry::CycloidGeometry &geometry,
               const DiscOutline               &outline,
               const std::string               &filename)
    {
      StepSummary summary;
      try
        {
          const double period =
            2. * dealii::numbers::PI * geometry.parameters().n_teeth;
          std::vector<double> t;
          const Handle(Geom_BSplineCurve) spline =
            refined_spline(geometry, outline.chord_tolerance, t);
          summary.n_spline_points = t.size();
          for (unsigned int i = 0; i < t.size(); ++i)
            summary.max_deviation =
              std::max(summary.max_deviation,
                       interval_deviation(geometry, spline, t, period, i, 8));
          std::ostringstream msg;
          msg << "the STEP spline deviates by " << summary.max_deviation
              << " mm from the profile, more than Profile/Chord tolerance = "
              << outline.chord_tolerance << " mm.";
          AssertThrow(summary.max_deviation <= outline.chord_tolerance,
                      dealii::ExcMessage(msg.str()));

          write_face(disc_face(spline, outline.holes), filename);
        }
      catch (const Standard_Failure &e)
        {
          AssertThrow(false,
                      dealii::ExcMessage(std::string("OpenCASCADE failed "
                                                     "writing '") +
                                         filename +
                                         "': " + e.GetMessageString()));
        }
      return summary;
    }
  } // namespace profile
} // namespace cycloid
