"""``image_view``: show a camera's images live in a window (node ``image_view``, anonymous).

The lab's "display the image from the robot" step where ROS's own image_view does not run
(Debian's image_view needs nodelet): ``rosrun tutorial_turtlebot image_view
image:=/camera/rgb/image_raw``. The window's title gives the topic, the image's size and
encoding, and the frames received per wall-clock second. Images larger than the screen are
shrunk to fit it; resizing the window scales the image (keeping its aspect ratio). ``q``,
Escape, closing the window or Ctrl-C quit.

Only the newest image is decoded and drawn: the subscriber keeps one message (queue_size 1,
a receive buffer that holds a whole frame), and frames that arrive while one is drawn are
counted in the rate but skipped, so the view never falls behind the camera. Decoding is
NumPy (no cv_bridge): :mod:`tutorial_turtlebot.lab.image_decoding`.

Without a display (no ``$DISPLAY``, or one that cannot be opened) it prints one line and exits
with status 2. An image it cannot decode (unknown encoding, sizes that do not add up) gets a
warning at most every 10 s, and the viewer keeps running.

Subscribes:
    image (sensor_msgs/Image): rgb8, bgr8, rgba8, bgra8, mono8, 8UC1, 8UC3, 8UC4, mono16,
        16UC1 (depth, mm) or 32FC1 (depth, m); remap it, as with image_view:
        ``image:=/camera/rgb/image_raw``.
    image/compressed (sensor_msgs/CompressedImage, JPEG or PNG): instead of ``image`` with
        ``_image_transport:=compressed``, or when ``image`` itself is remapped to a topic whose
        name ends in ``/compressed``.

Parameters (image_view's names):
    ~image_transport (str, default "raw"): "raw" or "compressed".
    ~do_dynamic_scaling (bool, default false): show 16UC1 and 32FC1 images over each frame's
        own minimum..maximum instead of the fixed range below.
    ~min_image_value, ~max_image_value (float, default 0 and 0): the range of 16UC1 (mm) and
        32FC1 (m) values shown black..white; both 0 means 0..10000 mm and 0..10 m.
"""
import sys
import threading
import time

import rospy
from sensor_msgs.msg import CompressedImage, Image

from .image_decoding import (FrameRate, ImageDecodeError, UnsupportedEncoding,
                             decode_compressed, decode_image, fit_scale, scaled_size)
from ..node_output import line_buffered

BUFF_SIZE = 1 << 24     # bytes: one 1920x1080 frame of any supported encoding (<= 8.3 MB)
POLL_PERIOD_MS = 10     # how often the window looks for a new frame (wall time)
TITLE_PERIOD = 0.5      # s of wall time between title updates (the rate is averaged over 2 s)
WARN_PERIOD = 10.0      # s between two warnings about undecodable images
NO_IMAGE_WARNING = 5.0  # s of wall time without any image before saying so (once)
SCREEN_MARGIN = (40, 80)  # px left free of the screen's width and height (borders, title, panel)
WAITING_SIZE = (480, 120)  # px: the window before the first image


class ImageView:
    """The window (a Tk root with one canvas) and the subscriber feeding it.

    ``on_image`` (rospy's thread) only keeps the newest message and counts it; ``poll`` (Tk's
    thread, every POLL_PERIOD_MS) decodes and draws the newest message, if a new one came.
    """

    def __init__(self, root, photo_class, pil_image, topic: str, compressed: bool,
                 scaling: dict):
        self.root = root
        self.photo_class = photo_class  # PIL.ImageTk.PhotoImage
        self.pil_image = pil_image      # the PIL.Image module
        self.compressed = compressed
        self.scaling = scaling          # keyword arguments of decode_image for depth images
        self._lock = threading.Lock()
        self._newest = None
        self._received = 0
        self._rate = FrameRate()
        self._started = time.monotonic()
        self._warned_no_image = False
        self._title_due = 0.0
        self._titled = (None, "")  # (self._frame, self._error) when the title was last set
        self._frame = None        # (width, height, encoding) of the image on screen
        self._error = ""          # why the last image was not shown
        self._view = None         # (width, height) available for the image, px
        self._photo = None
        import tkinter
        self.canvas = tkinter.Canvas(root, width=WAITING_SIZE[0], height=WAITING_SIZE[1],
                                     background="black", highlightthickness=0, borderwidth=0)
        self.canvas.pack(fill="both", expand=True)
        self._picture = self.canvas.create_image(0, 0, anchor="center")
        self._text = self.canvas.create_text(WAITING_SIZE[0] // 2, WAITING_SIZE[1] // 2,
                                             fill="white", anchor="center")
        self.canvas.bind("<Configure>", self._on_configure)
        for key in ("q", "<Escape>"):
            root.bind(key, lambda _event: self.close("closed by key"))
        root.protocol("WM_DELETE_WINDOW", lambda: self.close("window closed"))
        self.subscriber = rospy.Subscriber(topic, CompressedImage if compressed else Image,
                                           self.on_image, queue_size=1, buff_size=BUFF_SIZE)
        self.topic = self.subscriber.resolved_name
        self.canvas.itemconfigure(self._text, text="waiting for images on %s" % self.topic)
        self._set_title()

    def on_image(self, msg) -> None:
        """Subscriber callback: keep only the newest message."""
        with self._lock:
            self._newest = msg
            self._received += 1
            self._rate.tick(time.monotonic())

    def close(self, reason: str) -> None:
        """Stop the node and close the window."""
        rospy.signal_shutdown(reason)
        self.root.quit()

    def poll(self) -> None:
        """Draw the newest image if one came, refresh the title, and come back later."""
        if rospy.is_shutdown():
            self.root.quit()
            return
        with self._lock:
            msg, self._newest = self._newest, None
            received = self._received
        if msg is not None:
            self._show(msg)
        now = time.monotonic()
        if not received and not self._warned_no_image and now - self._started > NO_IMAGE_WARNING:
            self._warned_no_image = True
            rospy.logwarn("no image on %s after %g s: is a camera publishing there? "
                          "(rostopic list; the Burger has no camera)"
                          % (self.topic, NO_IMAGE_WARNING))
        if now >= self._title_due or (self._frame, self._error) != self._titled:
            self._set_title()
        self.root.after(POLL_PERIOD_MS, self.poll)

    def _show(self, msg) -> None:
        try:
            if self.compressed:
                rgb = decode_compressed(msg.data)
                encoding = msg.format.split(";")[0].strip() or "compressed"
            else:
                rgb = decode_image(msg.encoding, msg.width, msg.height, msg.step, msg.data,
                                   bool(msg.is_bigendian), **self.scaling)
                encoding = msg.encoding
        except UnsupportedEncoding as err:
            self._error = "unsupported encoding %r" % (msg.encoding,)
            rospy.logwarn_throttle(WARN_PERIOD, "image_view: %s on %s: not shown"
                                   % (err, self.topic))
            return
        except ImageDecodeError as err:
            self._error = "bad image"
            rospy.logwarn_throttle(WARN_PERIOD, "image_view: %s on %s: not shown"
                                   % (err, self.topic))
            return
        self._error = ""
        height, width = rgb.shape[:2]
        if self._frame is None or self._frame[:2] != (width, height):
            self._first_frame_of_size(width, height)
        self._frame = (width, height, encoding)
        scale = fit_scale(width, height, self._view[0], self._view[1], upscale=True)
        size = scaled_size(width, height, scale)
        picture = self.pil_image.fromarray(rgb)
        if size != (width, height):
            picture = picture.resize(size, self.pil_image.BILINEAR)
        if self._photo is not None and (self._photo.width(), self._photo.height()) == size:
            self._photo.paste(picture)
        else:
            self._photo = self.photo_class(picture)
            self.canvas.itemconfigure(self._picture, image=self._photo)
        self.canvas.itemconfigure(self._text, text="")

    def _first_frame_of_size(self, width: int, height: int) -> None:
        """Size the window for a new image size: the image's own, shrunk to fit the screen."""
        screen = (self.root.winfo_screenwidth() - SCREEN_MARGIN[0],
                  self.root.winfo_screenheight() - SCREEN_MARGIN[1])
        self._view = scaled_size(width, height, fit_scale(width, height, *screen))
        self.canvas.configure(width=self._view[0], height=self._view[1])
        self.root.geometry("")  # let the window follow the canvas's new requested size
        self._centre(*self._view)

    def _on_configure(self, event) -> None:
        """The canvas was resized (by us, or by the user dragging the window's border)."""
        if self._frame is not None:
            self._view = (max(1, event.width), max(1, event.height))
        self._centre(event.width, event.height)

    def _centre(self, width: int, height: int) -> None:
        self.canvas.coords(self._picture, width // 2, height // 2)
        self.canvas.coords(self._text, width // 2, height // 2)

    def _set_title(self) -> None:
        now = time.monotonic()
        self._title_due = now + TITLE_PERIOD
        self._titled = (self._frame, self._error)
        with self._lock:
            rate = self._rate.rate(now)
        self.root.title(window_title(self.topic, self._frame, rate, self._shown_scale(),
                                     self._error))

    def _shown_scale(self) -> float:
        if self._frame is None or self._photo is None:
            return 1.0
        return self._photo.width() / float(self._frame[0])


def window_title(topic: str, frame, rate: float, scale: float = 1.0, error: str = "") -> str:
    """The window's title, e.g. "/camera/rgb/image_raw  640x480 rgb8  30.0 fps"; ``frame`` is
    (width, height, encoding) of the image shown, or None before the first."""
    if frame is None:
        parts = [topic, "waiting for images"]
        if rate > 0:
            parts.append("%.1f fps" % rate)
    else:
        parts = [topic, "%dx%d %s" % frame, "%.1f fps" % rate]
        if abs(scale - 1.0) > 0.005:
            parts.append("shown at %d%%" % round(100 * scale))
    if error:
        parts.append(error)
    return "  ".join(parts)


def image_topic(image: str, transport: str):
    """(topic, compressed?) to subscribe, from the resolved name of ``image`` and the
    ~image_transport: image_transport's ``<image>/compressed`` for "compressed", and
    ``image`` itself as a CompressedImage topic when its name already ends in /compressed."""
    if transport == "compressed" and not image.endswith("/compressed"):
        return image + "/compressed", True
    return image, image.endswith("/compressed")


def _dynamic_scaling_params() -> dict:
    """decode_image's depth-scaling arguments from ~do_dynamic_scaling, ~min_image_value and
    ~max_image_value (a fatal error if they are not a bool and numbers)."""
    dynamic = rospy.get_param("~do_dynamic_scaling", False)
    low = rospy.get_param("~min_image_value", 0.0)
    high = rospy.get_param("~max_image_value", 0.0)
    if not isinstance(dynamic, bool):
        _fatal("parameter %s must be true or false, got %r"
               % (rospy.resolve_name("~do_dynamic_scaling"), dynamic))
    for name, value in (("~min_image_value", low), ("~max_image_value", high)):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            _fatal("parameter %s must be a number, got %r" % (rospy.resolve_name(name), value))
    if low == high == 0:
        return {"dynamic": dynamic}
    if high <= low:
        _fatal("parameter %s (%r) must be above %s (%r)"
               % (rospy.resolve_name("~max_image_value"), high,
                  rospy.resolve_name("~min_image_value"), low))
    return {"dynamic": dynamic, "value_range": (float(low), float(high))}


def _fatal(message: str) -> None:
    rospy.logfatal(message)
    sys.exit(2)


def _open_window():
    """(the tkinter module, Tk's root window, PIL.ImageTk.PhotoImage, PIL.Image); where there
    is no window to open, one line on stderr and exit status 2."""
    try:
        import tkinter
        from PIL import Image as PilImage, ImageTk
    except ImportError as err:
        sys.stderr.write("image_view: needs Tk and Pillow's ImageTk for Python 3 (%s); on "
                         "Debian/Ubuntu: sudo apt-get install python3-tk python3-pil.imagetk\n"
                         % err)
        sys.exit(2)
    try:
        root = tkinter.Tk(className="image_view")
    except tkinter.TclError as err:
        sys.stderr.write("image_view: cannot open a window: %s. Run it in a desktop session "
                         "(or over ssh -X, or under xvfb-run)\n" % str(err).strip())
        sys.exit(2)
    return tkinter, root, ImageTk.PhotoImage, PilImage


def main() -> None:
    """Entry point of scripts/image_view."""
    tkinter, root, photo_class, pil_image = _open_window()
    line_buffered()
    rospy.init_node("image_view", anonymous=True)
    transport = rospy.get_param("~image_transport", "raw")
    if transport not in ("raw", "compressed"):
        _fatal("parameter %s must be raw or compressed, got %r"
               % (rospy.resolve_name("~image_transport"), transport))
    topic, compressed = image_topic(rospy.resolve_name("image"), transport)
    view = ImageView(root, photo_class, pil_image, topic, compressed,
                     _dynamic_scaling_params())
    rospy.loginfo("image_view: showing %s in a window (q or Ctrl-C quits)", view.topic)
    root.after(POLL_PERIOD_MS, view.poll)
    try:
        root.mainloop()
    finally:
        rospy.signal_shutdown("image_view closed")
        try:
            root.destroy()
        except tkinter.TclError:  # already gone (e.g. with its display)
            pass
