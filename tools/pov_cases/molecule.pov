// A water molecule as a blob: one large oxygen, two hydrogens of lower strength pulled into it.
// Exercises: mixed positive strengths, `strength` keyword, #declare of numbers and vectors.
#version 3.7;
global_settings { assumed_gamma 1.0 }
#declare Bond = 1.35;
#declare Half = radians(104.5) / 2;
#declare H1 = <sin(Half), -cos(Half), 0> * Bond;
#declare H2 = <-sin(Half), -cos(Half), 0> * Bond;
camera { location <0.6, 1.2, -6> look_at <0, -0.3, 0> right x*image_width/image_height angle 40 }
light_source { <-10, 12, -14> color rgb <1, 1, 1> }
light_source { <12, 6, -10> color rgb 0.35 shadowless }
background { color rgb <0.2, 0.25, 0.3> }
blob {
  threshold 0.65
  sphere { <0, 0, 0>, 1.6, strength 2.0 }
  sphere { H1, 1.0, strength 1.0 }
  sphere { H2, 1.0, strength 1.0 }
  pigment { color rgb <0.85, 0.12, 0.1> }
  finish { ambient 0.12 diffuse 0.75 phong 0.6 phong_size 60 }
  rotate <15, -25, 0>
}
