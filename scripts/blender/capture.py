# A small capture from Blender Cycles for aalab's image scenes (docs/own-frames.md
# "Blender Cycles recipe"). Not part of `make test` (Blender is heavy); run by hand:
#
#   blender -b --factory-startup -P scripts/blender/capture.py -- OUT_DIR [W H FRAMES REF_SCALE REF_SPP]
#
# Writes into OUT_DIR: a still (still/frame.png, still/capture.exr: multilayer 1x passes,
# still/reference.exr, still/hires.exr: ids/depth at REF_SCALE x, plus the traps:
# still/frame-filmic.png, still/frame-threshold.png) and a sequence of FRAMES frames with a
# sub-pixel camera pan (seq/frame_%04d.png jittered, seq/ref_%04d.exr, seq/passes_%04d.exr
# with Vector), and the manifests still.json, seq.json.
#
# The scene: a ground plane, a cube casting a hard sun shadow, three thin wires (0.3, 0.5 and
# 0.8 px wide at the 1x size), a sky seen by camera rays only, direct light only (no
# bounces): every 1x sample is deterministic, so the 1x frame is a pixel-centre sample frame.
import json
import math
import os
import sys

import bpy
import numpy as np

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
OUT = os.path.abspath(argv[0] if argv else "capture")
W = int(argv[1]) if len(argv) > 1 else 160
H = int(argv[2]) if len(argv) > 2 else 90
FRAMES = int(argv[3]) if len(argv) > 3 else 8
SCALE = int(argv[4]) if len(argv) > 4 else 8
REF_SPP = int(argv[5]) if len(argv) > 5 else 4
PAN_PX = (0.37, 0.13)  # camera pan per frame, pixels at the 1x size (non-dyadic)
os.makedirs(os.path.join(OUT, "still"), exist_ok=True)
os.makedirs(os.path.join(OUT, "seq"), exist_ok=True)

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.engine = "CYCLES"
cy = scene.cycles
cy.device = "CPU"
cy.use_denoising = False
cy.use_adaptive_sampling = False
cy.max_bounces = 0  # direct light only: no noise from indirect paths
cy.caustics_reflective = False
cy.caustics_refractive = False
cy.light_sampling_threshold = 0.0  # the trap: the default 0.01 drops light samples (see docs)
cy.seed = 0
scene.render.use_motion_blur = False
scene.render.dither_intensity = 0.0  # the trap: default 1.0 adds noise to 8-bit output
scene.view_settings.view_transform = "Standard"  # the trap: Blender 3.4's default is Filmic
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.render.film_transparent = False
scene.render.threads_mode = "FIXED"
scene.render.threads = 2

# World: a sky colour for camera rays, black for lighting (Light Path: Is Camera Ray).
world = bpy.data.worlds.new("World")
scene.world = world
world.use_nodes = True
nt = world.node_tree
nt.nodes.clear()
bg = nt.nodes.new("ShaderNodeBackground")
bg.inputs["Color"].default_value = (0.35, 0.55, 0.85, 1.0)
black = nt.nodes.new("ShaderNodeBackground")
black.inputs["Color"].default_value = (0, 0, 0, 1)
lp = nt.nodes.new("ShaderNodeLightPath")
mix = nt.nodes.new("ShaderNodeMixShader")
out = nt.nodes.new("ShaderNodeOutputWorld")
nt.links.new(lp.outputs["Is Camera Ray"], mix.inputs["Fac"])
nt.links.new(black.outputs["Background"], mix.inputs[1])
nt.links.new(bg.outputs["Background"], mix.inputs[2])
nt.links.new(mix.outputs["Shader"], out.inputs["Surface"])


def material(name, rgb):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes["Principled BSDF"]
    p.inputs["Base Color"].default_value = (*rgb, 1.0)
    p.inputs["Specular"].default_value = 0.0
    p.inputs["Roughness"].default_value = 1.0
    return m


bpy.ops.mesh.primitive_plane_add(size=40, location=(0, 0, 0))
ground = bpy.context.object
ground.data.materials.append(material("ground", (0.6, 0.6, 0.55)))
ground.pass_index = 1
bpy.ops.mesh.primitive_cube_add(size=1.6, location=(-0.8, 0.6, 0.8), rotation=(0, 0, math.radians(27)))
cube = bpy.context.object
cube.data.materials.append(material("cube", (0.8, 0.25, 0.1)))
cube.pass_index = 2

# Camera: 50 mm, looking at the scene from the front and above.
cam_data = bpy.data.cameras.new("cam")
cam_data.sensor_fit = "HORIZONTAL"
cam = bpy.data.objects.new("cam", cam_data)
scene.collection.objects.link(cam)
scene.camera = cam
cam.location = (0.0, -9.0, 3.2)
cam.rotation_euler = (math.radians(74), 0, 0)

# Wires: thin cylinders across the view at y = 0, widths 0.3 / 0.5 / 0.8 px at the 1x size.
dist = 9.0  # roughly the camera distance at y = 0
px_world = 2 * dist * math.tan(cam_data.angle_x / 2) / W
for i, width_px in enumerate((0.3, 0.5, 0.8)):
    r = 0.5 * width_px * px_world
    bpy.ops.mesh.primitive_cylinder_add(vertices=12, radius=r, depth=14, location=(0.5, 0.0, 1.6 + 0.55 * i),
                                        rotation=(0, math.radians(90), math.radians(4 + 3 * i)))
    w = bpy.context.object
    w.data.materials.append(material("wire%d" % i, (0.05, 0.05, 0.05)))
    w.pass_index = 3 + i

sun_data = bpy.data.lights.new("sun", "SUN")
sun_data.energy = 3.0
sun_data.angle = 0.0  # hard shadow: no penumbra noise
sun = bpy.data.objects.new("sun", sun_data)
scene.collection.objects.link(sun)
sun.rotation_euler = (math.radians(40), math.radians(25), math.radians(30))

vl = scene.view_layers[0]
vl.use_pass_z = True
vl.use_pass_object_index = True


def set_jitter(dx, dy):
    # Sub-pixel sample offset (pixels, x right, y down) via the camera shift (units of the
    # sensor width with HORIZONTAL fit): shifting the view right moves the sample right.
    cam_data.shift_x = dx / W
    cam_data.shift_y = -dy / W


def pan_location(t):
    # The camera moves by PAN_PX per frame in 1x pixels of the y = 0 plane (x right, y down).
    return (t * PAN_PX[0] * px_world, -9.0, 3.2 - t * PAN_PX[1] * px_world / math.sin(math.radians(74)))


def set_pan(t):
    cam.location = pan_location(t)


def compositor_aa(on):
    # Blender's own post AA (the compositor's Anti-Aliasing node, SMAA-based): the
    # "user's own pipeline" whose frames become a supplied row.
    scene.use_nodes = on
    if not on:
        return
    ct = scene.node_tree
    ct.nodes.clear()
    rl = ct.nodes.new("CompositorNodeRLayers")
    aa = ct.nodes.new("CompositorNodeAntiAliasing")
    comp = ct.nodes.new("CompositorNodeComposite")
    ct.links.new(rl.outputs["Image"], aa.inputs["Image"])
    ct.links.new(aa.outputs["Image"], comp.inputs["Image"])


def render(path, w, h, spp, filter_width, fmt, depth="8", multilayer=False, vector=False):
    scene.render.resolution_x = w
    scene.render.resolution_y = h
    scene.render.resolution_percentage = 100
    cy.samples = spp
    cy.pixel_filter_type = "BOX"
    cy.filter_width = filter_width
    vl.use_pass_vector = vector
    s = scene.render.image_settings
    if multilayer:
        s.file_format = "OPEN_EXR_MULTILAYER"
        s.color_depth = "32"
        s.exr_codec = "ZIP"
    elif fmt == "EXR":
        s.file_format = "OPEN_EXR"
        s.color_depth = "32"
        s.color_mode = "RGB"
    else:
        s.file_format = "PNG"
        s.color_mode = "RGB"
        s.color_depth = depth
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def box_reference(hires_exr, out_exr):
    # Display-linear box filter: Standard view = clamp to [0, 1] of the scene-linear value
    # (exposure 0), averaged over each 1x pixel's SCALE x SCALE block.
    img = bpy.data.images.load(hires_exr)
    w, h = img.size
    a = np.array(img.pixels[:], dtype=np.float64).reshape(h, w, 4)[:, :, :3]
    bpy.data.images.remove(img)
    a = np.clip(a, 0.0, 1.0)
    small = a.reshape(h // SCALE, SCALE, w // SCALE, SCALE, 3).mean(axis=(1, 3))
    out_img = bpy.data.images.new("ref", w // SCALE, h // SCALE, alpha=True, float_buffer=True)
    # The trap: Blender 3.4 saves a float image whose colour space is "Linear" through the
    # view transform (the EXR then holds sRGB-encoded values); "Non-Color" writes the values.
    out_img.colorspace_settings.name = "Non-Color"
    rgba = np.concatenate([small, np.ones(small.shape[:2] + (1,))], axis=2)
    out_img.pixels = rgba.astype(np.float32).ravel().tolist()
    out_img.filepath_raw = out_exr
    out_img.file_format = "OPEN_EXR"
    out_img.save()
    bpy.data.images.remove(out_img)
    return small


def srgb(v):
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)


# --- the still ---
S = os.path.join(OUT, "still")
set_pan(0)
set_jitter(0, 0)
render(os.path.join(S, "frame.png"), W, H, 1, 0.01, "PNG")  # pixel-centre samples
compositor_aa(True)
render(os.path.join(S, "blender-aa.png"), W, H, 1, 0.01, "PNG")
compositor_aa(False)
render(os.path.join(S, "capture.exr"), W, H, 1, 0.01, "EXR", multilayer=True)  # 1x ids and depth
render(os.path.join(S, "hires.exr"), W * SCALE, H * SCALE, REF_SPP, 1.0, "EXR", multilayer=True)
render(os.path.join(S, "hires-rgb.exr"), W * SCALE, H * SCALE, REF_SPP, 1.0, "EXR")
small = box_reference(os.path.join(S, "hires-rgb.exr"), os.path.join(S, "reference.exr"))
os.remove(os.path.join(S, "hires-rgb.exr"))
# Trap 1: the same frame through Filmic (Blender 3.4's default view transform).
scene.view_settings.view_transform = "Filmic"
render(os.path.join(S, "frame-filmic.png"), W, H, 1, 0.01, "PNG")
scene.view_settings.view_transform = "Standard"
# Trap 2: the light sampling threshold left at its default 0.01 for the 1x frame.
cy.light_sampling_threshold = 0.01
render(os.path.join(S, "frame-threshold.png"), W, H, 1, 0.01, "PNG")
cy.light_sampling_threshold = 0.0

# --- the sequence: jittered 1x frames (a TAA input), references, passes with Vector ---
Q = os.path.join(OUT, "seq")
halton = []
for i in range(1, FRAMES + 1):
    def h(b, n):
        f, r = 1.0, 0.0
        while n > 0:
            f /= b
            r += f * (n % b)
            n //= b
        return r
    halton.append([round(h(2, i) - 0.5, 6), round(h(3, i) - 0.5, 6)])
# The pan is keyframed (the Vector pass needs the camera's motion between frames); the jitter
# is set on each frame without keyframes, so the vectors hold the motion without the jitter.
scene.frame_start, scene.frame_end = 1, FRAMES
for t in range(FRAMES):
    cam.location = pan_location(t)
    cam.keyframe_insert("location", frame=t + 1)
for fc in cam.animation_data.action.fcurves:
    for k in fc.keyframe_points:
        k.interpolation = "LINEAR"
    fc.extrapolation = "LINEAR"
for t in range(FRAMES):
    scene.frame_set(t + 1)
    set_jitter(*halton[t])
    render(os.path.join(Q, "frame_%04d.png" % t), W, H, 1, 0.01, "PNG")
    render(os.path.join(Q, "passes_%04d.exr" % t), W, H, 1, 0.01, "EXR", multilayer=True, vector=True)
    set_jitter(0, 0)
    compositor_aa(True)
    render(os.path.join(Q, "blender-aa_%04d.png" % t), W, H, 1, 0.01, "PNG")
    compositor_aa(False)
    render(os.path.join(Q, "hires_%04d.exr" % t), W * SCALE, H * SCALE, REF_SPP, 1.0, "EXR")
    box_reference(os.path.join(Q, "hires_%04d.exr" % t), os.path.join(Q, "ref_%04d.exr" % t))
    os.remove(os.path.join(Q, "hires_%04d.exr" % t))
json.dump({"jitter": halton, "pan_px": PAN_PX, "width": W, "height": H, "scale": SCALE, "ref_spp": REF_SPP},
          open(os.path.join(OUT, "capture.json"), "w"), indent=1)
# The manifests (docs/own-frames.md): the still and the sequence.
info = {"renderer": "Blender %s Cycles, %dx%d box-filtered in display-linear light" % (bpy.app.version_string, SCALE, SCALE),
        "samples_per_pixel": SCALE * SCALE * REF_SPP}
json.dump({"aalab_image_scene": 1, "description": "Blender Cycles capture (scripts/blender/capture.py)", "views": [
    {"name": "blender-still", "frame": "still/frame.png", "reference": "still/reference.exr", "reference_info": info,
     "object_ids": "still/capture.exr", "depth": "still/capture.exr",
     "outputs": [{"name": "blender-aa", "frame": "still/blender-aa.png"}]}]},
    open(os.path.join(OUT, "still.json"), "w"), indent=1)
json.dump({"aalab_image_scene": 1, "description": "Blender Cycles sequence: camera pan (%g, %g) px/frame, Halton jitter" % PAN_PX,
           "views": [
    {"name": "blender-pan", "sequence": {"frames": FRAMES}, "frame": "seq/frame_%04d.png", "reference": "seq/ref_%04d.exr",
     "reference_info": info, "object_ids": "seq/passes_%04d.exr", "depth": "seq/passes_%04d.exr", "jitter": halton,
     "motion_vectors": {"path": "seq/passes_%04d.exr", "direction": "to_previous", "y": "up"},
     "outputs": [{"name": "blender-aa", "frame": "seq/blender-aa_%04d.png"}]}]},
    open(os.path.join(OUT, "seq.json"), "w"), indent=1)
print("capture written to", OUT)
