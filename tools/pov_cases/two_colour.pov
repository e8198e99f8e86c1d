// A two-colour water molecule: the oxygen and one hydrogen carry textures of their own, the other
// hydrogen takes the blob's; POV-Ray mixes the textures by each component's |strength * field|.
// Exercises: per-component pigment, finish and texture, a blob-level texture for the rest.
#version 3.7;
global_settings { assumed_gamma 1.0 }
#declare Bond = 1.35;
#declare Half = radians(104.5) / 2;
camera { location <0.4, 1.0, -6> look_at <0, -0.3, 0> right x*image_width/image_height angle 40 }
light_source { <-10, 12, -14> color rgb <1, 1, 1> }
light_source { <12, 6, -10> color rgb 0.35 shadowless }
background { color rgb <0.2, 0.25, 0.3> }
blob {
  threshold 0.65
  sphere { <0, 0, 0>, 1.6, strength 2.0
    pigment { color rgb <0.85, 0.12, 0.1> }
    finish { ambient 0.1 diffuse 0.7 phong 0.6 phong_size 60 }
  }
  sphere { <sin(Half), -cos(Half), 0> * Bond, 1.0, strength 1.0
    texture { pigment { color rgb <0.9, 0.9, 0.88> } finish { ambient 0.1 diffuse 0.8 } }
  }
  sphere { <-sin(Half), -cos(Half), 0> * Bond, 1.0, strength 1.0 }
  pigment { color rgb <0.2, 0.4, 0.9> }
  finish { ambient 0.1 diffuse 0.8 specular 0.3 roughness 0.02 }
  rotate <15, -25, 0>
}
