// An orthographic camera without `angle`: the view is `right` wide and `up` tall in world units.
// A blob minus a box, beside a sphere, on a floor.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { orthographic location <30, 26, -40> look_at <0, 4, 0> right 44*x up 33*y }
light_source { <300, 600, -400> color rgb 1 }
background { color rgb <0.45, 0.55, 0.75> }
plane { y, 0 pigment { color rgb <0.62, 0.6, 0.55> } }
difference {
  blob {
    threshold 0.5
    sphere { <0, 6, 0>, 10, 1 }
    sphere { <6, 8, -3>, 7, 1 }
    pigment { color rgb <0.85, 0.45, 0.35> }
  }
  box { <0, 6, -12>, <12, 14, 0> pigment { color rgb <0.95, 0.85, 0.7> } }
}
sphere { <-12, 3, -6>, 3 pigment { color rgb <0.4, 0.6, 0.85> } }
