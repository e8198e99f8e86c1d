// A melted candle: a cylinder body with a negative ring that dents the rim, drips as small
// spheres, and a wick hole punched by a negative sphere. Exercises: cylinder components,
// negative strengths, a component scaled after it is placed.
#version 3.7;
global_settings { assumed_gamma 1.0 ambient_light rgb <1, 0.95, 0.9> }
camera { location <0, 5.5, -9> look_at <0, 2.2, 0> right x*image_width/image_height angle 42 }
light_source { <-6, 12, -8> color rgb <1.0, 0.95, 0.85> }
background { color rgb <0.05, 0.04, 0.06> }
blob {
  threshold 0.6
  cylinder { <0, 0, 0>, <0, 3.2, 0>, 1.7, 2.0 }
  sphere { <0, 3.55, 0>, 1.0, -2.5 }
  sphere { <0.0, 3.3, 0>, 0.35, -3 }
  sphere { <0, 0, 0>, 0.5, 1.2 scale <1, 1.9, 1> translate <0.95, 2.35, -0.55> }
  sphere { <0, 0, 0>, 0.45, 1.1 scale <1, 1.6, 1> translate <-0.9, 2.6, -0.6> }
  sphere { <0, 0, 0>, 0.4, 1.0 scale <1, 2.2, 1> translate <0.2, 2.2, -1.1> }
  cylinder { <0, 3.0, 0>, <0, 4.1, 0>, 0.12, 3.5 }
  pigment { color rgb <0.9, 0.85, 0.7> }
  finish { ambient 0.15 diffuse 0.7 }
}
