// A dumbbell on a floor under a spotlight with fading and a 5x5 area light: soft shadows and a
// lit cone. Exercises: spotlight (radius, falloff, tightness, point_at), area_light with
// adaptive, fade_distance/fade_power, a finish with specular and brilliance, a plane and a box.
#version 3.7;
global_settings { assumed_gamma 1.0 ambient_light rgb 0.6 }
camera { location <0, 4, -9> look_at <0, 0.4, 0> right x*image_width/image_height angle 40 }
light_source { <3, 8, -4> color rgb <1, 0.95, 0.9>
  spotlight point_at <0, 0, 0> radius 12 falloff 25 tightness 2
  fade_distance 8 fade_power 1 }
light_source { <-6, 6, -3> color rgb 0.5
  area_light <1.5, 0, 0>, <0, 0, 1.5>, 5, 5 adaptive 1 }
background { color rgb <0.12, 0.12, 0.15> }
blob {
  threshold 0.5
  sphere { <-1.4, 0.6, 0>, 1.2, 1 }
  sphere { <1.4, 0.6, 0>, 1.2, 1 }
  cylinder { <-1.4, 0.6, 0>, <1.4, 0.6, 0>, 0.6, 1.2 }
  pigment { color rgb <0.3, 0.6, 0.35> }
  finish { ambient 0.15 diffuse 0.7 brilliance 1.5 specular 0.5 roughness 0.03 }
}
plane { y, -0.6 pigment { color rgb <0.7, 0.68, 0.62> } finish { ambient 0.1 diffuse 0.8 } }
box { <-0.5, -0.6, -0.5>, <0.5, 0.2, 0.5> rotate 30*y translate <2.6, 0, 1.2>
  pigment { color rgb <0.5, 0.3, 0.2> } }
