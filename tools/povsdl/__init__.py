"""Reading POV-Ray 3.7 scene files into softtrace scenes (tools/pov2softtrace.py).

lexer: the file as tokens with their line and column; values: numbers, vectors and colours;
affine: POV-Ray's transformations and the change of frame; scene: the statements and objects.
Every refusal is a PovError carrying the line and column of the construct it names.
"""
