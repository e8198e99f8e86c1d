// The POV-Ray 3.1 `component` form and colors.inc names, still found in older scenes.
#version 3.7;
#include "colors.inc"
global_settings { assumed_gamma 1.0 }
camera { location <0, 0, -6> direction <0, 0, 1.5> look_at <0, 0, 0> }
light_source { <-15, 30, -25> color White }
light_source { <15, 30, -25> color Gray50 }
background { color MidnightBlue }
blob {
  threshold 0.6
  component 1.0, 1.0, <0.75, 0, 0>
  component 1.0, 1.0, <-0.375, 0.64952, 0>
  component 1.0, 1.0, <-0.375, -0.64952, 0>
  component -0.5, 0.6, <0, 0, -0.4>
  pigment { color Orange }
  finish { ambient 0.1 diffuse 0.7 phong 1 }
  rotate 30*y
}
