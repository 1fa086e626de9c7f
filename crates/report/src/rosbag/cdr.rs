//! A little CDR encoder: the serialisation of ROS 2 messages (OMG XCDR1, little-endian, as
//! Fast DDS and rosbag2 write it).
//!
//! A message starts with the 4-byte encapsulation header `00 01 00 00` (CDR, little-endian,
//! no options). Every primitive is aligned to its own size (at most 8), counted from the end
//! of that header; padding bytes are 0. A string is its length in bytes including a closing
//! NUL (`u32`), its UTF-8 bytes and the NUL; a sequence is its element count (`u32`) and its
//! elements; a nested message is its fields in order, with no header of its own.

/// The encapsulation header of a little-endian CDR message.
const LITTLE_ENDIAN_CDR: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// A CDR message being written.
///
/// ```
/// use mason_report::Cdr;
/// let mut c = Cdr::new();
/// c.u8(1);
/// c.f64(0.5); // aligned to 8 after the header: 7 bytes of padding
/// c.string("hi");
/// let bytes = c.finish();
/// assert_eq!(&bytes[..5], &[0, 1, 0, 0, 1]);
/// assert_eq!(bytes.len(), 4 + 8 + 8 + 4 + 3);
/// ```
#[derive(Clone, Debug)]
pub struct Cdr {
    bytes: Vec<u8>,
}

impl Default for Cdr {
    fn default() -> Self {
        Cdr::new()
    }
}

impl Cdr {
    /// An empty message: its encapsulation header only.
    pub fn new() -> Self {
        let mut bytes = Vec::with_capacity(256);
        bytes.extend_from_slice(&LITTLE_ENDIAN_CDR);
        Cdr { bytes }
    }

    /// Pads with zeros to a multiple of `n` bytes after the header.
    fn align(&mut self, n: usize) {
        let offset = self.bytes.len() - LITTLE_ENDIAN_CDR.len();
        let pad = (n - offset % n) % n;
        self.bytes.resize(self.bytes.len() + pad, 0);
    }

    /// A `uint8` (or `byte`).
    pub fn u8(&mut self, v: u8) {
        self.bytes.push(v);
    }

    /// A `bool`: one byte, 0 or 1.
    pub fn bool(&mut self, v: bool) {
        self.bytes.push(u8::from(v));
    }

    /// An `int32`.
    pub fn i32(&mut self, v: i32) {
        self.align(4);
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }

    /// A `uint32` (also a string's length and a sequence's count).
    pub fn u32(&mut self, v: u32) {
        self.align(4);
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }

    /// A `float32`.
    pub fn f32(&mut self, v: f32) {
        self.align(4);
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }

    /// A `float64`.
    pub fn f64(&mut self, v: f64) {
        self.align(8);
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }

    /// A `string`: length with the closing NUL, the bytes, the NUL. A string longer than
    /// `u32::MAX - 1` bytes cannot be a ROS 2 string; it is cut there.
    pub fn string(&mut self, s: &str) {
        let bytes = &s.as_bytes()[..s.len().min(u32::MAX as usize - 1)];
        self.u32(bytes.len() as u32 + 1);
        self.bytes.extend_from_slice(bytes);
        self.bytes.push(0);
    }

    /// The element count of a sequence (`T[]`); the caller writes the elements next.
    pub fn sequence(&mut self, len: usize) {
        self.u32(u32::try_from(len).unwrap_or(u32::MAX));
    }

    /// The message's bytes.
    pub fn finish(self) -> Vec<u8> {
        self.bytes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primitives_are_aligned_to_their_size_after_the_header() {
        let mut c = Cdr::new();
        c.bool(true); // offset 0
        c.i32(-2); // padded to 4
        c.u8(7); // 8
        c.f32(1.5); // padded to 12
        c.f64(-0.25); // padded to 16 (after the header, not from the buffer's start)
        c.u32(9); // 24
        let b = c.finish();
        let mut want = vec![0, 1, 0, 0, 1, 0, 0, 0];
        want.extend_from_slice(&(-2i32).to_le_bytes());
        want.extend_from_slice(&[7, 0, 0, 0]);
        want.extend_from_slice(&1.5f32.to_le_bytes());
        want.extend_from_slice(&(-0.25f64).to_le_bytes());
        want.extend_from_slice(&9u32.to_le_bytes());
        assert_eq!(b, want);
    }

    #[test]
    fn strings_carry_their_nul_and_the_next_field_is_realigned() {
        let mut c = Cdr::new();
        c.string("");
        c.string("abc");
        c.f64(1.0);
        let b = c.finish();
        // "" → len 1, NUL; "abc" at 5 is padded to 8: len 4, bytes, NUL → 16; f64 at 16.
        assert_eq!(&b[4..9], &[1, 0, 0, 0, 0]);
        assert_eq!(&b[9..12], &[0, 0, 0]);
        assert_eq!(&b[12..20], &[4, 0, 0, 0, b'a', b'b', b'c', 0]);
        assert_eq!(&b[20..28], &1.0f64.to_le_bytes());
        assert_eq!(b.len(), 28);
    }

    #[test]
    fn an_empty_sequence_is_its_count() {
        let mut c = Cdr::new();
        c.u8(1);
        c.sequence(0);
        assert_eq!(c.finish(), [0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0]);
    }
}
