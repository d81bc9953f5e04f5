# Render what Blender Cycles makes of an IES file: a point light (radius 0)
# with an IES Texture node at the origin, a white diffuse plane at z = -1,
# seen from above by an orthographic camera, direct light only.
#
# Run:  blender -b --factory-startup --python scripts/blender_ies_render.py -- FILE.ies OUT.exr RES HALF
# RES: image side in pixels; HALF: the plane's half width (the image covers
# x, y in [-HALF, HALF] at z = -1). Each pixel (row 0 at +y) holds the
# radiance of the plane there, proportional to I(d) cos(theta) / r^2 with
# d = (x, y, -1) / r: tests/it/engines.rs (blender_render_matches_the_emulation)
# turns it back into the intensity Cycles used and compares it with
# photosolid's emulation (scripts/blender-cross-check.sh runs both).
import sys

import bpy

argv = sys.argv[sys.argv.index("--") + 1 :]
ies_path, out_path, res, half = argv[0], argv[1], int(argv[2]), float(argv[3])

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.world = None
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 64  # 4 left a few pixels 0.4 % off their mirror images
scene.cycles.light_sampling_threshold = 0.0  # no probabilistic termination of light samples
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 0  # direct light only
scene.cycles.filter_width = 0.01  # every sample at the pixel centre
scene.render.resolution_x = res
scene.render.resolution_y = res
scene.render.resolution_percentage = 100
scene.view_settings.view_transform = "Standard"
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.filepath = out_path

light = bpy.data.lights.new("ies", "POINT")
light.shadow_soft_size = 0.0
light.energy = 1000.0
light.use_nodes = True
nodes = light.node_tree.nodes
ies = nodes.new("ShaderNodeTexIES")
ies.mode = "EXTERNAL"
ies.filepath = ies_path
light.node_tree.links.new(ies.outputs["Fac"], nodes["Emission"].inputs["Strength"])
light_object = bpy.data.objects.new("ies", light)
scene.collection.objects.link(light_object)

mesh = bpy.data.meshes.new("plane")
s = 1.05 * half
mesh.from_pydata([(-s, -s, -1.0), (s, -s, -1.0), (s, s, -1.0), (-s, s, -1.0)], [], [(0, 1, 2, 3)])
material = bpy.data.materials.new("white")
material.use_nodes = True
mnodes = material.node_tree.nodes
mnodes.remove(mnodes["Principled BSDF"])
diffuse = mnodes.new("ShaderNodeBsdfDiffuse")
diffuse.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
material.node_tree.links.new(diffuse.outputs["BSDF"], mnodes["Material Output"].inputs["Surface"])
mesh.materials.append(material)
plane = bpy.data.objects.new("plane", mesh)
scene.collection.objects.link(plane)

camera = bpy.data.cameras.new("camera")
camera.type = "ORTHO"
camera.ortho_scale = 2.0 * half
camera.clip_start = 0.01
camera_object = bpy.data.objects.new("camera", camera)
camera_object.location = (0.0, 0.0, -0.5)
scene.collection.objects.link(camera_object)
scene.camera = camera_object

bpy.ops.render.render(write_still=True)
