"""Frame sinks: orientation, naming, atomic PNG writes, memory and video output."""

import os

import imageio.v3 as iio
import numpy as np
import pytest

from vgxsim.sinks import (
    MemorySink,
    PNGSequenceSink,
    SinkError,
    VideoSink,
    open_sink,
    to_top_down,
    write_image,
    write_png,
)


def bottom_up_image(h=4, w=5, seed=0):
    """An RGBA image whose rows are all different; row 0 is the bottom row."""
    rng = np.random.default_rng(seed)
    img = rng.integers(0, 256, size=(h, w, 4), dtype=np.uint8)
    img[..., 3] = 255
    return img


def test_to_top_down_flips_rows():
    img = bottom_up_image()
    top = to_top_down(img)
    assert np.array_equal(top[0], img[-1]) and np.array_equal(top[-1], img[0])
    assert top.flags["C_CONTIGUOUS"]
    assert to_top_down(img, alpha=False).shape == (4, 5, 3)


def test_rejects_bad_images():
    sink = MemorySink()
    with pytest.raises(TypeError):
        sink.write(np.zeros((2, 2, 4), np.float32))
    with pytest.raises(ValueError):
        sink.write(np.zeros((2, 2), np.uint8))
    with pytest.raises(ValueError):
        sink.write(np.zeros((0, 2, 4), np.uint8))


def test_png_sequence_naming_and_orientation(tmp_path):
    out = tmp_path / "a" / "b"  # created, parents included
    imgs = [bottom_up_image(seed=i) for i in range(3)]
    with PNGSequenceSink(out) as sink:
        for img in imgs:
            sink.write(img)
    names = sorted(os.listdir(out))
    assert names == ["frame_0000.png", "frame_0001.png", "frame_0002.png"]
    assert sink.count == 3 and sink.paths == [str(out / n) for n in names]
    for name, img in zip(names, imgs, strict=True):
        data = iio.imread(out / name)
        assert data.shape == (4, 5, 3)  # RGB by default
        assert np.array_equal(data[0], img[-1, :, :3])  # file's top row = array's last row
        assert np.array_equal(data, img[::-1, :, :3])


def test_png_sequence_prefix_alpha_and_start(tmp_path):
    img = bottom_up_image()
    img[..., 3] = 0  # IRIS programs often leave alpha at 0
    sink = PNGSequenceSink(tmp_path, prefix="shot", digits=2, start=7, alpha=True)
    sink.write(img)
    sink.close()
    data = iio.imread(tmp_path / "shot07.png")
    assert data.shape == (4, 5, 4) and np.array_equal(data, img[::-1])
    with pytest.raises(ValueError):
        sink.write(img)  # closed


def test_image_write_is_atomic(tmp_path, monkeypatch):
    path = tmp_path / "frame_0000.png"
    write_image(path, bottom_up_image(seed=1)[..., :3])
    good = path.read_bytes()

    from PIL import Image

    def broken(image, fh, format=None, **params):  # (write_image's encoder)
        fh.write(b"\x89PNG half")
        raise RuntimeError("disk on fire")

    monkeypatch.setattr(Image.Image, "save", broken)
    with pytest.raises(SinkError, match="frame_0000.png: disk on fire"):
        write_image(path, bottom_up_image(seed=2), overwrite=True)
    assert path.read_bytes() == good  # old file intact
    assert sorted(os.listdir(tmp_path)) == ["frame_0000.png"]  # no temp file left
    sink = PNGSequenceSink(tmp_path / "frames")
    with pytest.raises(SinkError, match="frame_0000.png"):
        sink.write(bottom_up_image(seed=2))
    assert os.listdir(tmp_path / "frames") == [] and sink.count == 0


def test_write_png_single_image(tmp_path):
    img = bottom_up_image(3, 2)
    write_png(tmp_path / "one.png", img)
    assert np.array_equal(iio.imread(tmp_path / "one.png"), img[::-1, :, :3])
    with pytest.raises(SinkError, match="missing"):
        write_png(tmp_path / "missing" / "x.png", img)


def test_unwritable_directory_is_named(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(SinkError, match="file"):
        PNGSequenceSink(blocker / "sub")


def test_memory_sink_keeps_top_down_copies():
    img = bottom_up_image()
    sink = MemorySink()
    sink.write(img)
    img[:] = 0  # later changes to the framebuffer do not leak into stored frames
    sink.write(img)
    assert len(sink) == 2 and sink.count == 2
    assert sink[0].shape == (4, 5, 4)
    assert np.array_equal(sink[0], bottom_up_image()[::-1])
    assert not sink[1].any()


def test_gif_round_trip(tmp_path):
    path = tmp_path / "movie.gif"
    # few flat colours, so the GIF palette reproduces them exactly
    imgs = []
    for i in range(3):
        img = np.zeros((6, 8, 4), np.uint8)
        img[:3] = (255, 0, 0, 255)  # bottom half red
        img[3:] = (0, 0, 255, 255)  # top half blue
        img[0, i] = (0, 255, 0, 255)  # a green pixel on the bottom row, moving
        imgs.append(img)
    with VideoSink(path, fps=10) as sink:
        for img in imgs:
            sink.write(img)
    frames = iio.imread(path, index=None)
    assert frames.shape[:3] == (3, 6, 8)
    for got, img in zip(frames, imgs, strict=True):
        assert np.array_equal(got[..., :3], img[::-1, :, :3])
    assert tuple(frames[0][0, 0, :3]) == (0, 0, 255)  # top row is blue


def test_video_rejects_size_change_and_bad_suffix(tmp_path):
    sink = VideoSink(tmp_path / "v.gif")
    sink.write(np.zeros((4, 4, 4), np.uint8))
    with pytest.raises(ValueError, match="v.gif"):
        sink.write(np.zeros((4, 6, 4), np.uint8))
    sink.close()
    sink.close()  # idempotent
    with pytest.raises(ValueError):
        VideoSink(tmp_path / "v.avi")


def test_video_without_frames_writes_nothing(tmp_path):
    VideoSink(tmp_path / "empty.gif").close()
    assert not (tmp_path / "empty.gif").exists()


def test_mp4_without_ffmpeg_names_the_package(tmp_path, monkeypatch):
    from vgxsim.sinks import mp4

    monkeypatch.setattr(mp4, "ffmpeg_problem", lambda: "no ffmpeg in this test")
    with pytest.raises(ImportError, match="imageio-ffmpeg"):
        VideoSink(tmp_path / "m.mp4")
    assert not (tmp_path / "m.mp4").exists()


def test_mp4_round_trip(tmp_path):
    pytest.importorskip("imageio_ffmpeg")
    path = tmp_path / "m.mp4"
    with VideoSink(path, fps=24) as sink:
        for i in range(5):
            img = np.zeros((15, 17, 4), np.uint8)  # odd size: padded to 16x18
            img[:, :, i % 3] = 200
            sink.write(img)
    frames = iio.imread(path, index=None, plugin="FFMPEG")
    assert frames.shape[0] == 5 and frames.shape[1:3] == (16, 18)


def test_open_sink_chooses_by_spec(tmp_path):
    assert isinstance(open_sink(None), MemorySink)
    mem = MemorySink()
    assert open_sink(mem) is mem
    assert isinstance(open_sink(tmp_path), PNGSequenceSink)
    assert isinstance(open_sink(str(tmp_path / "new_dir")), PNGSequenceSink)
    assert isinstance(open_sink(str(tmp_path / "x.d") + os.sep), PNGSequenceSink)
    gif = open_sink(tmp_path / "a.GIF", fps=12)
    assert isinstance(gif, VideoSink) and gif.fps == 12
    with pytest.raises(ValueError, match="out.png"):
        open_sink(tmp_path / "out.png")


def flat(h, w, rgb):
    img = np.zeros((h, w, 4), np.uint8)
    img[..., :3] = rgb
    img[..., 3] = 255
    return img


def test_gif_is_complete_after_every_frame(tmp_path):
    path = tmp_path / "live.gif"
    colours = [(255, 0, 0), (0, 255, 0), (0, 0, 255), (0, 255, 0)]
    sink = VideoSink(path, fps=10)
    for n, rgb in enumerate(colours, start=1):
        sink.write(flat(3, 5, rgb))
        # read while the sink is still open: every frame so far, exactly
        got = iio.imread(path, index=None)
        assert got.shape[:3] == (n, 3, 5)
        assert [tuple(f[0, 0, :3]) for f in got] == colours[:n]  # repeats kept too
    sink.close()
    assert path.read_bytes().endswith(b";")  # the GIF trailer


def test_gif_frame_with_more_than_256_colours(tmp_path):
    img = np.zeros((24, 32, 4), np.uint8)
    img[..., 0] = np.arange(32 * 24).reshape(24, 32) % 256
    img[..., 1] = np.arange(32 * 24).reshape(24, 32) // 256 * 80  # 768 colours
    with VideoSink(tmp_path / "many.gif") as sink:
        sink.write(img)
        sink.write(flat(24, 32, (9, 9, 9)))
    frames = iio.imread(tmp_path / "many.gif", index=None)
    assert frames.shape[:3] == (2, 24, 32)
    # quantized to a 256-entry palette: close, not exact; the flat frame exact
    assert np.abs(frames[0][..., :3].astype(int) - img[::-1, :, :3]).mean() < 8
    assert (frames[1][..., :3] == 9).all()


def test_png_folder_of_an_earlier_run_is_refused_or_replaced(tmp_path):
    out = tmp_path / "f"
    out.mkdir()
    for name in ("frame_0000.png", "frame_0007.png", "win2_frame_0000.png", "notes.txt",
                 ".frame_0008.png.123.0.tmp"):  # what a killed run was writing
        (out / name).write_bytes(b"old")
    with pytest.raises(SinkError, match=r"f already holds 4 frame files.*--overwrite"):
        PNGSequenceSink(out)
    assert len(os.listdir(out)) == 5  # refused: nothing touched
    sink = PNGSequenceSink(out, overwrite=True)
    assert sorted(os.listdir(out)) == ["notes.txt"]  # every old frame gone at once
    sink.write(bottom_up_image())
    assert sorted(os.listdir(out)) == ["frame_0000.png", "notes.txt"]


def test_existing_video_is_refused_or_replaced(tmp_path):
    path = tmp_path / "v.gif"
    path.write_bytes(b"an earlier movie")
    with pytest.raises(SinkError, match=r"v\.gif exists.*--overwrite"):
        VideoSink(path)
    assert path.read_bytes() == b"an earlier movie"
    with VideoSink(path, overwrite=True) as sink:
        sink.write(flat(2, 2, (1, 2, 3)))
    assert iio.imread(path, index=None).shape[:3] == (1, 2, 2)


@pytest.mark.parametrize("suffix", [".gif", ".mp4"])
def test_full_video_target_fails_when_the_sink_is_made(tmp_path, suffix):
    if suffix == ".mp4":
        pytest.importorskip("imageio_ffmpeg")
    full = tmp_path / f"full{suffix}"
    full.symlink_to("/dev/full")  # every write: ENOSPC
    with pytest.raises(SinkError, match=rf"full\{suffix}: No space left on device"):
        VideoSink(full, overwrite=True)


@pytest.mark.parametrize("target", ["file/frames", "/proc/vgxsim-frames"])
def test_unwritable_frame_folder_fails_when_the_sink_is_made(tmp_path, target):
    (tmp_path / "file").write_text("a file, not a folder")
    folder = target if target.startswith("/") else str(tmp_path / target)
    with pytest.raises(SinkError, match=folder):
        open_sink(folder)


def test_unwritable_video_folder(tmp_path):
    with pytest.raises(SinkError, match="missing.*does not exist"):
        VideoSink(tmp_path / "missing" / "v.gif")
    with pytest.raises(SinkError, match="vgxsim.gif"):
        VideoSink("/proc/vgxsim.gif")


def test_write_image_format_from_the_name(tmp_path):
    top = bottom_up_image(6, 8)[::-1]
    write_image(tmp_path / "a.jpg", top)
    write_image(tmp_path / "a.JPEG", top)
    write_image(tmp_path / "a.tif", top)
    write_image(tmp_path / "a.png", top)
    assert (tmp_path / "a.jpg").read_bytes()[:3] == b"\xff\xd8\xff"  # JPEG SOI marker
    assert (tmp_path / "a.JPEG").read_bytes()[:3] == b"\xff\xd8\xff"
    assert (tmp_path / "a.tif").read_bytes()[:4] in (b"II*\x00", b"MM\x00*")
    assert (tmp_path / "a.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert np.array_equal(iio.imread(tmp_path / "a.tif", plugin="pillow")[..., :4], top)  # lossless
    with pytest.raises(SinkError, match=r"a\.bmp.*\.png"):
        write_image(tmp_path / "a.bmp", top)
    with pytest.raises(SinkError, match=r"a\.png exists"):
        write_image(tmp_path / "a.png", top, overwrite=False)
    with pytest.raises(SinkError, match="must end in .png"):
        write_png(tmp_path / "b.jpg", bottom_up_image())
    assert not (tmp_path / "a.bmp").exists() and not (tmp_path / "b.jpg").exists()


def test_an_empty_placeholder_is_not_an_earlier_output(tmp_path):
    import tempfile

    fd, tmp = tempfile.mkstemp(suffix=".gif", dir=tmp_path)  # as an atomic writer makes
    os.close(fd)
    with VideoSink(tmp) as sink:  # nothing to lose: no --overwrite needed
        sink.write(flat(2, 2, (7, 7, 7)))
    assert iio.imread(tmp, index=None).shape[:3] == (1, 2, 2)


@pytest.mark.parametrize("name", ["a.png", "a.jpg", "a.tif"])
@pytest.mark.parametrize("channels", [3, 4])
def test_write_image_writes_what_imageio_writes(tmp_path, name, channels):
    """write_image calls Pillow itself (imageio's plugin imports every Pillow format
    plugin first, a cost of every start): the file is the one imageio's pillow
    plugin writes, byte for byte, and a non-contiguous view is written as its
    values."""
    top = bottom_up_image(9, 7, seed=channels)[::-1][..., :channels]
    write_image(tmp_path / name, top)
    want = top[..., :3] if name.endswith(".jpg") else top
    ref = iio.imwrite("<bytes>", np.ascontiguousarray(want), extension=name[1:],
                      plugin="pillow")
    assert (tmp_path / name).read_bytes() == ref
    if not name.endswith(".jpg"):  # lossless
        assert np.array_equal(iio.imread(tmp_path / name, plugin="pillow"), top)
