// Triangle meshes: a tetrahedron `mesh` (with inside_vector: solid) cut out of a sphere, and a
// `mesh2` tetrahedron beside it; tools/pov2softtrace.py writes both to OBJ files.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <6, 5, -8> look_at <0, 0.5, 0> right x*image_width/image_height angle 40 }
light_source { <30, 60, -40> color rgb 1 }
background { color rgb <0.45, 0.55, 0.75> }
difference {
  sphere { <0, 0.5, 0>, 1.6 pigment { rgb <0.9, 0.5, 0.4> } }
  mesh {
    triangle { <0, 2, 0>, <1, 0, 1>, <1, 0, -1> }
    triangle { <0, 2, 0>, <1, 0, -1>, <-1, 0, 0> }
    triangle { <0, 2, 0>, <-1, 0, 0>, <1, 0, 1> }
    triangle { <1, 0, 1>, <-1, 0, 0>, <1, 0, -1> }
    inside_vector <0, 0, 1>
    translate <0.6, 0.2, -1>
    pigment { rgb <0.3, 0.6, 0.9> }
  }
}
mesh2 {
  vertex_vectors { 4, <2, 0, 2>, <3, 0, 2>, <2, 1, 2>, <2, 0, 3> }
  face_indices { 4, <0, 1, 2>, <0, 3, 1>, <0, 2, 3>, <1, 3, 2> }
  pigment { rgb <0.5, 0.8, 0.4> }
  scale 1.5 translate <-3.5, 0, 0>
}
