// A blob cut by a plane and merged with a box, on a floor: CSG with a blob across (difference,
// merge, intersection), parts that take the CSG's texture, a cut face with its cutter's pigment.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <34, 24, -46> right x*image_width/image_height look_at <-2, 5, 0> angle 40 }
light_source { <300, 600, -400> color rgb 1 }
background { color rgb <0.45, 0.55, 0.75> }
plane { y, 0 pigment { color rgb <0.62, 0.6, 0.55> } }
merge {
  difference {
    blob {
      threshold 0.5
      sphere { <0, 5, 0>, 9, 1 }
      sphere { <5, 9, 3>, 6, 1 }
      pigment { color rgb <0.85, 0.45, 0.35> }
    }
    plane { <-0.7, -0.5, 0.5>, -8 pigment { color rgb <0.95, 0.85, 0.7> } }
  }
  intersection {
    box { <-12, 0, -5>, <-3, 6, 3> }
    sphere { <-7.5, 3, -1>, 5.5 }
  }
  pigment { color rgb <0.75, 0.7, 0.35> }
}
