// cutaway_textures: a red blob minus a box that has no texture of its own. With the keyword the
// cut faces show the blob's red (without it they would take the default texture); lit by a
// light that reaches the cut faces, over a floor that takes their shadow.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <30, 26, -40> right x*image_width/image_height look_at <0, 6, 0> angle 24 }
light_source { <250, 500, -350> color rgb 1 }
background { color rgb <0.45, 0.55, 0.75> }
plane { y, 0 pigment { color rgb <0.62, 0.6, 0.55> } }
difference {
  blob {
    threshold 0.5
    sphere { <0, 6, 0>, 9, 1 }
    sphere { <-4, 9, 2>, 6, 1 }
    pigment { color rgb <0.9, 0.15, 0.1> }
    finish { phong 0.4 }
  }
  box { <1, 5, -10>, <12, 16, 1> }
  cutaway_textures
}
