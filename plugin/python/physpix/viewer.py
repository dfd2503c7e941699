"""python -m physpix.viewer [scene.json]: a pygame window on a world, and its painting interface.

It draws the bodies' sprites and World.debug_draw's overlay; a mouse pulls bodies through a MOUSE joint, blasts
holes, and paints weight, solid pixels or holes into the body under it while the world runs. A painted body is
saved as a scene body's PNG planes. Headless (SDL_VIDEODRIVER=dummy): --frames N --screenshot out.png, and
--script FILE of timed strokes, so that painting is testable. pygame is optional: pip install physpix[viewer].
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import enums
from .image import load_png, save_png
from .world import Body, BodyType, Joint, World

INSTALL_HINT = "physpix.viewer needs pygame: pip install 'physpix[viewer]' (or: pip install pygame)"
DT = 1.0 / 60.0
# Keys 1..6 toggle these overlay bits, in this order.
OVERLAYS = [enums.DEBUG_DRAW_OUTLINES, enums.DEBUG_DRAW_AABBS, enums.DEBUG_DRAW_CONTACTS, enums.DEBUG_DRAW_JOINTS,
            enums.DEBUG_DRAW_CENTERS, enums.DEBUG_DRAW_VELOCITIES]
TOOLS = ("grab", "paint", "solid", "erase")
HELP = ("1-6 overlays  w weight map  space pause  s/→ step  g grab  p paint weight  o solid  e erase  "
        "[ ] radius  -/= weight  k save body  q quit")


def _snapshot_id(body: Body) -> str:
    """A body's handle as a snapshot's world.json stores it: generation << 32 | (slot + 1) (lib/core/handle.h)."""
    slot, gen = body.id & 0xFFFFF, (body.id >> 40) & 0x1FFFFF
    return "0x%016x" % (gen << 32 | (slot + 1))


def body_planes(body: Body) -> Tuple[Dict[str, Any], Dict[str, np.ndarray]]:
    """A body's scene entry and its planes (mask, weights, sprite as RGBA arrays) as a snapshot writes them: the
    only place the library hands out every field of a body's def."""
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "snap"
        body.world.save_snapshot(folder)
        doc = json.loads((folder / "world.json").read_text(encoding="utf-8"))
        want = _snapshot_id(body)
        entry = next(b for b in doc["bodies"] if b["handle"] == want)
        planes = {kind: load_png(folder / entry[kind]) for kind in ("mask", "weights", "sprite") if kind in entry}
    for key in ("handle", "serial", "state", "mask", "weights", "sprite"):
        entry.pop(key, None)
    return entry, planes


def save_body(body: Body, folder: os.PathLike, name: str = "painted") -> Path:
    """Write folder/<name>_mask.png, _weights.png, _sprite.png (if it has one) and folder/<name>.json, a scene holding
    just this body at its pose, which World.load_scene reads back with the same mass properties."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    entry, planes = body_planes(body)
    entry["name"] = name
    for kind, rgba in planes.items():
        save_png(folder / f"{name}_{kind}.png", rgba)
        entry[kind] = f"{name}_{kind}.png"
    scene = folder / f"{name}.json"
    scene.write_text(json.dumps({"bodies": [entry]}, indent=1) + "\n", encoding="utf-8")
    return scene


def default_world() -> World:
    """The scene without a file: a floor, a plank on a pivot and a few crates."""
    world = World(gravity=(0, 980))
    world.create_body(np.ones((40, 960), np.uint8), type="static", position=(480, 520))
    world.create_body(np.ones((20, 12), np.uint8), type="static", position=(480, 490))
    plank = world.create_body(np.ones((12, 300), np.uint8), position=(480, 474), density=1)
    world.create_joint("revolute", None, plank, anchor_a=(480, 474))
    for i in range(5):
        world.create_body(np.ones((32, 32), np.uint8), position=(200 + 40 * i, 300 - 40 * (i % 2)))
    return world


class Viewer:
    """A world, its view and its tools; `frame()` steps and draws one frame, `run()` a whole session."""

    def __init__(self, world: World, size: Optional[Tuple[int, int]] = None, save_dir: os.PathLike = ".") -> None:
        import pygame  # noqa: F401 (checked by main; here so that a Viewer needs it too)
        self.pg = pygame
        self.world = world
        cam = world.camera
        self.size = size or (cam.width, cam.height)
        # A smaller window shows the same view, scaled.
        self.zoom = cam.zoom * min(self.size[0] / cam.width, self.size[1] / cam.height)
        self.center = cam.center
        self.flags = enums.DEBUG_DRAW_ALL
        self.show_weights = True
        self.paused = False
        self.tool = "grab"
        self.radius = 8.0
        self.weight = 255
        self.selected: Optional[Body] = None
        self.save_dir = Path(save_dir)
        self.frame_index = 0
        self._sprites: Dict[int, Any] = {}
        self._weights: Dict[int, Any] = {}
        self._drag: Optional[Joint] = None
        self._press: Optional[Tuple[int, int]] = None
        self._font: Any = None
        self._script: List[Dict[str, Any]] = []

    # -- coordinates
    def to_screen(self, p: Sequence[float]) -> Tuple[float, float]:
        return (float(p[0] - self.center[0]) * self.zoom + self.size[0] / 2,
                float(p[1] - self.center[1]) * self.zoom + self.size[1] / 2)

    def to_world(self, s: Sequence[float]) -> Tuple[float, float]:
        return ((s[0] - self.size[0] / 2) / self.zoom + self.center[0],
                (s[1] - self.size[1] / 2) / self.zoom + self.center[1])

    @staticmethod
    def local_to_world(body: Body, q: Sequence[float]) -> Tuple[float, float]:
        """A bitmap point (px from the top-left) in world px."""
        (px, py), (vx, vy), a = body.position, body.pivot, body.angle
        dx, dy = q[0] - vx, q[1] - vy
        return px + dx * math.cos(a) - dy * math.sin(a), py + dx * math.sin(a) + dy * math.cos(a)

    # -- tools
    def body_at(self, at: Sequence[float], radius: float = 0.0) -> Optional[Body]:
        """The body under a world point, a moving one before a static one; else the nearest within radius."""
        hits = self.world.query_point(at) or (self.world.query_circle(at, radius) if radius > 0 else [])
        hits.sort(key=lambda b: b.type == BodyType.STATIC)
        return hits[0] if hits else None

    def edited(self, body: Optional[Body] = None) -> None:
        """Forget the cached pictures of what an edit changed (all of them when it may have touched any)."""
        for cache in (self._sprites, self._weights):
            if body is None:
                cache.clear()
            else:
                cache.pop(body.id, None)

    def brush(self, tool: str, at: Sequence[float], radius: float, weight: int = 255) -> int:
        """paint (weight 1..255), solid (weight 255) or erase a circle of the body under `at`; pixels changed."""
        target = self.body_at(at, radius) or self.selected
        if target is None:
            return 0
        self.selected = target
        if tool == "erase":
            changed = target.erase_circle(at, radius)
        else:
            changed = target.paint_circle(at, radius, weight if tool == "paint" else 255)
        self.edited(target)
        return changed

    def blast(self, at: Sequence[float], radius: float = 24.0, impulse_per_length: float = 6000.0) -> int:
        """World.explode: erase a circle out of every body and push the moving bodies near it outward, at full
        strength within radius and to nothing at three radii (a 24 px crate of density 1 leaves at up to 250 px/s);
        returns the pixels erased."""
        changed = self.world.explode(at, radius, falloff=2 * radius, impulse_per_length=impulse_per_length,
                                     erase_radius=radius)
        self.edited()
        return changed

    def grab(self, at: Sequence[float]) -> bool:
        body = self.body_at(at)
        if body is None or body.type != BodyType.DYNAMIC:
            return False
        self.selected = body
        self._drag = self.world.create_joint("mouse", None, body, anchor_a=at, anchor_b=at,
                                             max_force=1000.0 * body.mass)
        self._drag.set_target(at)
        return True

    def release(self) -> None:
        if self._drag is not None:
            try:
                self._drag.destroy()
            except Exception:  # the body was destroyed (erased away) under the joint
                pass
            self._drag = None

    def save(self, body: Optional[Body] = None, name: str = "painted", folder: Optional[os.PathLike] = None) -> Path:
        body = body or self.selected
        if body is None:
            raise ValueError("no body to save: paint or click one first")
        return save_body(body, folder or self.save_dir, name)

    def apply(self, action: Dict[str, Any]) -> None:
        """One scripted action: {"tool": paint|solid|erase|blast|save|grab|drag|release, "at": [x, y] world px,
        "radius", "weight", for blast "impulse_per_length", for save "dir" and "name"}."""
        tool = action["tool"]
        at = action.get("at", (0.0, 0.0))
        if tool in ("paint", "solid", "erase"):
            self.brush(tool, at, float(action.get("radius", self.radius)), int(action.get("weight", self.weight)))
        elif tool == "blast":
            self.blast(at, float(action.get("radius", 24.0)), float(action.get("impulse_per_length", 6000.0)))
        elif tool == "save":
            body = self.body_at(at) if "at" in action else None
            self.save(body, action.get("name", "painted"), action.get("dir"))
        elif tool == "grab":
            self.grab(at)
        elif tool == "drag":
            if self._drag is not None:
                self._drag.set_target(at)
        elif tool == "release":
            self.release()
        else:
            raise ValueError(f"script: unknown tool {tool!r}")

    # -- drawing
    def _sprite(self, body: Body) -> Any:
        pg = self.pg
        if body.id not in self._sprites:
            rgba = np.ascontiguousarray(body.read_rgba())
            h, w = rgba.shape[:2]
            self._sprites[body.id] = pg.image.frombuffer(rgba.tobytes(), (w, h), "RGBA").convert_alpha() \
                if pg.display.get_surface() else pg.image.frombuffer(rgba.tobytes(), (w, h), "RGBA")
        return self._sprites[body.id]

    def _weight_map(self, body: Body) -> Any:
        """The weight plane as a translucent heat map: transparent where empty, redder where heavier."""
        pg = self.pg
        if body.id not in self._weights:
            wt = body.read_weights()
            rgba = np.zeros(wt.shape + (4,), np.uint8)
            rgba[..., 0] = 255
            rgba[..., 1] = 255 - wt
            rgba[..., 3] = np.where(wt > 0, 160, 0)
            h, w = wt.shape
            self._weights[body.id] = pg.image.frombuffer(rgba.tobytes(), (w, h), "RGBA")
        return self._weights[body.id]

    def _blit_body(self, surface: Any, body: Body, image: Any) -> None:
        pg = self.pg
        w, h = body.size
        centre = self.to_screen(self.local_to_world(body, (w / 2, h / 2)))
        turned = pg.transform.rotozoom(image, -math.degrees(body.angle), self.zoom)
        surface.blit(turned, turned.get_rect(center=(round(centre[0]), round(centre[1]))))

    def draw(self, surface: Any) -> None:
        pg = self.pg
        surface.fill((24, 26, 32))
        bodies = self.world.bodies()
        for body in bodies:
            self._blit_body(surface, body, self._sprite(body))
        if self.selected is not None and self.selected in bodies and self.show_weights:
            self._blit_body(surface, self.selected, self._weight_map(self.selected))
        lower, upper = self.to_world((0, 0)), self.to_world(self.size)
        segs = self.world.debug_draw(self.flags, lower, upper)
        half = np.array(self.size, np.float64) / 2
        ends = [((segs[k] - np.asarray(self.center)) * self.zoom + half).tolist() for k in ("a", "b")]
        for a, b, c in zip(ends[0], ends[1], segs["rgba"].tolist()):
            pg.draw.line(surface, (c >> 24 & 255, c >> 16 & 255, c >> 8 & 255), a, b)
        if self.selected is not None and self.selected in bodies:
            x, y = self.to_screen(self.local_to_world(self.selected, self.selected.center_of_mass))
            pg.draw.circle(surface, (255, 255, 0), (round(x), round(y)), 6, 2)
            pg.draw.line(surface, (255, 255, 0), (x - 9, y), (x + 9, y))
            pg.draw.line(surface, (255, 255, 0), (x, y - 9), (x, y + 9))
        if self._font is not None:
            state = "paused" if self.paused else "running"
            text = f"{self.tool} r={self.radius:g} weight={self.weight}  {state}  frame {self.frame_index}  (h: keys)"
            surface.blit(self._font.render(text, True, (230, 230, 230)), (8, 6))

    # -- a session
    def step(self) -> None:
        self.world.step(DT)
        self.frame_index += 1
        if self.world.scheduled_edits():  # a scene's timed edits may change any body's pixels
            self.edited()

    def handle(self, event: Any) -> bool:
        """One pygame event; False to quit."""
        pg = self.pg
        if event.type == pg.QUIT:
            return False
        if event.type == pg.KEYDOWN:
            key = event.key
            if key in (pg.K_q, pg.K_ESCAPE):
                return False
            if pg.K_1 <= key <= pg.K_6:
                self.flags ^= OVERLAYS[key - pg.K_1]
            elif key == pg.K_w:
                self.show_weights = not self.show_weights
            elif key == pg.K_SPACE:
                self.paused = not self.paused
            elif key in (pg.K_s, pg.K_RIGHT):
                self.paused = True
                self.step()
            elif key in (pg.K_g, pg.K_p, pg.K_o, pg.K_e):
                self.tool = {pg.K_g: "grab", pg.K_p: "paint", pg.K_o: "solid", pg.K_e: "erase"}[key]
            elif key == pg.K_LEFTBRACKET:
                self.radius = max(1.0, self.radius - 2)
            elif key == pg.K_RIGHTBRACKET:
                self.radius += 2
            elif key == pg.K_MINUS:
                self.weight = max(1, self.weight - 16)
            elif key == pg.K_EQUALS:
                self.weight = min(255, self.weight + 16)
            elif key == pg.K_k and self.selected is not None:
                print(f"physpix.viewer: saved {self.save()}")
            elif key == pg.K_h:
                print(HELP)
        elif event.type == pg.MOUSEBUTTONDOWN:
            at = self.to_world(event.pos)
            if event.button == 3 or (event.button == 1 and self.tool == "grab" and not self.grab(at)):
                self.blast(at)
            self._press = event.pos if event.button == 1 else None
        elif event.type == pg.MOUSEMOTION and self._drag is not None:
            self._drag.set_target(self.to_world(event.pos))
        elif event.type == pg.MOUSEBUTTONUP and event.button == 1:
            self.release()
            self._press = None
        return True

    def run(self, frames: int = 0, script: Sequence[Dict[str, Any]] = (), screenshot: Optional[os.PathLike] = None,
            interactive: bool = True) -> None:
        """Run until closed, or until `frames` frames have run in all (0: no limit); a script action runs before the
        step that its frame begins."""
        pg = self.pg
        pg.display.init()
        pg.font.init()
        surface = pg.display.set_mode(self.size)
        pg.display.set_caption("physpix viewer")
        self._font = pg.font.Font(None, 18)
        clock = pg.time.Clock()
        # Actions wait across runs, so a run that stops at a frame leaves that frame's actions to the next.
        self._script = sorted(self._script + list(script), key=lambda a: int(a.get("frame", 0)))
        pending = self._script
        self.edited()  # the surfaces of an earlier display are gone
        running = True
        while running and (frames <= 0 or self.frame_index < frames):
            while pending and int(pending[0].get("frame", 0)) <= self.frame_index:
                self.apply(pending.pop(0))
            for event in pg.event.get():
                running = self.handle(event) and running
            if self._press is not None and self.tool != "grab":
                self.brush(self.tool, self.to_world(pg.mouse.get_pos()), self.radius, self.weight)
            if not self.paused or not interactive:
                self.step()
            self.draw(surface)
            pg.display.flip()
            if interactive:
                clock.tick(60)
        if screenshot is not None:
            write_screenshot(surface, screenshot)
        pg.quit()


def write_screenshot(surface: Any, path: os.PathLike) -> None:
    import pygame
    w, h = surface.get_size()
    data = (pygame.image.tobytes if hasattr(pygame.image, "tobytes") else pygame.image.tostring)(surface, "RGBA")
    rgba = np.frombuffer(data, np.uint8).reshape(h, w, 4).copy()
    rgba[..., 3] = 255  # the window has no alpha channel: tobytes leaves it 0
    save_png(path, rgba)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m physpix.viewer", description=__doc__.split("\n")[0],
                                     epilog="keys: " + HELP)
    parser.add_argument("scene", nargs="?", help="a scene JSON file (default: a floor, a plank on a pivot, crates)")
    parser.add_argument("--frames", type=int, default=0, help="run this many frames, then exit (0: until closed)")
    parser.add_argument("--screenshot", help="write the last frame to this PNG")
    parser.add_argument("--script", help="a JSON list of timed actions, e.g. "
                        '{"frame": 10, "tool": "paint", "at": [x, y], "radius": 8, "weight": 255}')
    parser.add_argument("--size", type=int, nargs=2, metavar=("W", "H"), help="window size (default: the camera's)")
    parser.add_argument("--save-dir", default=".", help="where the k key saves a painted body (default: .)")
    args = parser.parse_args(argv)
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    try:
        import pygame  # noqa: F401
    except ImportError:
        print(INSTALL_HINT, file=sys.stderr)
        return 2
    world = World.load_scene(args.scene) if args.scene else default_world()
    script: List[Dict[str, Any]] = []
    if args.script:
        script = json.loads(Path(args.script).read_text(encoding="utf-8"))
    headless = args.frames > 0
    Viewer(world, tuple(args.size) if args.size else None, args.save_dir).run(
        args.frames, script, args.screenshot, interactive=not headless)
    return 0


if __name__ == "__main__":
    sys.exit(main())
