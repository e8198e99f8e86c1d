// Focal blur: three blobs at three depths, the middle one in focus (focal_point on it), the
// others blurred; `variance 0` makes POV-Ray take every one of its blur_samples, as softtrace
// does.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera {
  location <0, 8, -40> look_at <0, 4, 0> right x*image_width/image_height angle 40
  aperture 3 focal_point <0, 4, 0> blur_samples 64 variance 0
}
light_source { <300, 600, -400> color rgb 1 }
background { color rgb <0.45, 0.55, 0.75> }
plane { y, 0 pigment { color rgb <0.62, 0.6, 0.55> } }
blob {
  threshold 0.5
  sphere { <-9, 4, -14>, 7, 1 }
  sphere { <-6, 6, -14>, 5, 1 }
  pigment { color rgb <0.85, 0.45, 0.35> }
}
blob {
  threshold 0.5
  sphere { <0, 4, 0>, 8, 1 }
  sphere { <3, 7, 1>, 5, 1 }
  pigment { color rgb <0.45, 0.8, 0.4> }
}
blob {
  threshold 0.5
  sphere { <12, 5, 20>, 9, 1 }
  sphere { <16, 8, 20>, 6, 1 }
  pigment { color rgb <0.4, 0.55, 0.9> }
}
