//! glTF accessors decoded into plain arrays, every read bounds-checked: float and (normalized
//! or not) integer components, as core glTF and `KHR_mesh_quantization` allow them, become
//! `f32`; index accessors become `u32`. A damaged accessor is an error naming it, never a
//! panic or a read past its buffer.

use gltf::accessor::{DataType, Dimensions};
use gltf::Accessor;

/// Why an accessor cannot be read, said for the user (the accessor is named).
pub type AccessorResult<T> = Result<T, String>;

/// The bytes of every buffer of the file, by buffer index.
pub struct Buffers(pub Vec<Vec<u8>>);

impl Buffers {
    /// The bytes of all buffers together.
    pub fn total_len(&self) -> usize {
        self.0.iter().map(Vec::len).sum()
    }
}

/// Where an accessor's elements lie: the bytes of its buffer view, the offset of the first
/// element, the distance between elements, and each element's size.
struct Layout<'a> {
    bytes: &'a [u8],
    start: usize,
    stride: usize,
    element: usize,
}

fn component_size(t: DataType) -> usize {
    match t {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

fn multiplicity(d: Dimensions) -> usize {
    match d {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 | Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

fn layout<'a>(a: &Accessor<'_>, buffers: &'a Buffers) -> AccessorResult<Layout<'a>> {
    let name = format!("accessor {}", a.index());
    if a.sparse().is_some() {
        return Err(format!("{name}: sparse accessors are not supported"));
    }
    let Some(view) = a.view() else {
        return Err(format!("{name} has no bufferView"));
    };
    let buffer = buffers
        .0
        .get(view.buffer().index())
        .ok_or_else(|| format!("{name}: its buffer {} is missing", view.buffer().index()))?;
    let view_end = view.offset().checked_add(view.length());
    let bytes = match view_end {
        Some(end) if end <= buffer.len() => &buffer[view.offset()..end],
        _ => {
            return Err(format!(
                "bufferView {} (bytes {}..+{}) runs past the end of buffer {} ({} bytes)",
                view.index(),
                view.offset(),
                view.length(),
                view.buffer().index(),
                buffer.len()
            ))
        }
    };
    let element = component_size(a.data_type()) * multiplicity(a.dimensions());
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!(
            "{name}: byteStride {stride} is smaller than an element ({element} bytes)"
        ));
    }
    let count = a.count();
    let needed = match count {
        0 => Some(0),
        n => (n - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(element))
            .and_then(|x| x.checked_add(a.offset())),
    };
    match needed {
        Some(n) if n <= bytes.len() => {}
        _ => {
            return Err(format!(
                "{name}: {count} elements of {element} bytes every {stride} bytes from byte {} \
                 do not fit in bufferView {} ({} bytes)",
                a.offset(),
                view.index(),
                bytes.len()
            ))
        }
    }
    Ok(Layout {
        bytes,
        start: a.offset(),
        stride,
        element,
    })
}

/// Reads the `k`th component of type `t` in `b` as a float: normalized integers are mapped
/// to 0..=1 (unsigned) or -1..=1 (signed) as the glTF specification says.
fn component(b: &[u8], k: usize, t: DataType, normalized: bool) -> f32 {
    let s = component_size(t) * k;
    let u16_at = |i: usize| u16::from_le_bytes([b[i], b[i + 1]]);
    match t {
        DataType::F32 => f32::from_le_bytes([b[s], b[s + 1], b[s + 2], b[s + 3]]),
        DataType::U32 => u32::from_le_bytes([b[s], b[s + 1], b[s + 2], b[s + 3]]) as f32,
        DataType::U8 if normalized => f32::from(b[s]) / 255.0,
        DataType::U8 => f32::from(b[s]),
        DataType::I8 if normalized => (f32::from(b[s] as i8) / 127.0).max(-1.0),
        DataType::I8 => f32::from(b[s] as i8),
        DataType::U16 if normalized => f32::from(u16_at(s)) / 65535.0,
        DataType::U16 => f32::from(u16_at(s)),
        DataType::I16 if normalized => (f32::from(u16_at(s) as i16) / 32767.0).max(-1.0),
        DataType::I16 => f32::from(u16_at(s) as i16),
    }
}

/// Reads an attribute accessor of `N` components per element (`VEC2`, `VEC3`) as floats;
/// `VEC4` colours are read with `N = 3` through [`read_floats_prefix`].
pub fn read_floats<const N: usize>(
    a: &Accessor<'_>,
    buffers: &Buffers,
) -> AccessorResult<Vec<[f32; N]>> {
    if multiplicity(a.dimensions()) != N {
        return Err(format!(
            "accessor {} has type {:?}, expected one of {N} components",
            a.index(),
            a.dimensions()
        ));
    }
    read_floats_prefix(a, buffers)
}

/// Reads the first `N` components of every element of `a` as floats.
pub fn read_floats_prefix<const N: usize>(
    a: &Accessor<'_>,
    buffers: &Buffers,
) -> AccessorResult<Vec<[f32; N]>> {
    if multiplicity(a.dimensions()) < N {
        return Err(format!(
            "accessor {} has type {:?}, expected at least {N} components",
            a.index(),
            a.dimensions()
        ));
    }
    let l = layout(a, buffers)?;
    let (t, normalized) = (a.data_type(), a.normalized());
    let mut out = Vec::with_capacity(a.count());
    if t == DataType::F32 {
        for i in 0..a.count() {
            let at = l.start + i * l.stride;
            let e = &l.bytes[at..at + l.element];
            out.push(std::array::from_fn(|k| {
                f32::from_le_bytes([e[4 * k], e[4 * k + 1], e[4 * k + 2], e[4 * k + 3]])
            }));
        }
    } else {
        for i in 0..a.count() {
            let at = l.start + i * l.stride;
            let e = &l.bytes[at..at + l.element];
            out.push(std::array::from_fn(|k| component(e, k, t, normalized)));
        }
    }
    Ok(out)
}

/// Reads an index accessor (`SCALAR` of unsigned bytes, shorts or ints).
pub fn read_indices(a: &Accessor<'_>, buffers: &Buffers) -> AccessorResult<Vec<u32>> {
    let t = a.data_type();
    if a.dimensions() != Dimensions::Scalar
        || !matches!(t, DataType::U8 | DataType::U16 | DataType::U32)
        || a.normalized()
    {
        return Err(format!(
            "accessor {} holds indices but is {:?} {:?}: expected SCALAR unsigned byte, short or int",
            a.index(),
            a.dimensions(),
            t
        ));
    }
    let l = layout(a, buffers)?;
    Ok((0..a.count())
        .map(|i| {
            let e = &l.bytes[l.start + i * l.stride..];
            match t {
                DataType::U8 => u32::from(e[0]),
                DataType::U16 => u32::from(u16::from_le_bytes([e[0], e[1]])),
                _ => u32::from_le_bytes([e[0], e[1], e[2], e[3]]),
            }
        })
        .collect())
}
