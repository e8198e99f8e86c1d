// Bent pipes and flattened pebbles: capsules rotated, then stretched (a shear), an ellipsoid from a
// per-axis scale, and one component placed with a full `matrix`. Exercises: affine placement in
// any order on components and on the whole blob.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0, 6, -11> look_at <0, 0.5, 0> right x*image_width/image_height angle 45 }
light_source { <8, 14, -12> color rgb 1 }
light_source { <-10, 4, -6> color rgb 0.3 }
background { color rgb <0.35, 0.4, 0.5> }
blob {
  threshold 0.5
  cylinder { <-2, 0, 0>, <2, 0, 0>, 0.9, 1 rotate 30*z scale <1, 0.5, 1.5> translate <-1.5, 1, 0> }
  cylinder { <0, -1.5, 0>, <0, 1.5, 0>, 0.8, 1.2 rotate <40, 0, 25> scale <1.6, 1, 0.7> }
  sphere { <0, 0, 0>, 1.2, 1 scale <2.2, 0.6, 1.1> translate <2.2, -0.5, 0.5> }
  sphere { <0, 0, 0>, 1.0, 1.5 matrix < 1, 0.4, 0,  0, 1, 0.3,  0.5, 0, 1,  -2.5, -1, 1 > }
  sphere { <0.5, 0.2, 0>, 0.7, -1.5 }
  pigment { color rgb <0.3, 0.55, 0.8> }
  finish { diffuse 0.8 specular 0.4 roughness 0.02 }
  rotate 20*y
  scale <1, 1.1, 1>
}
