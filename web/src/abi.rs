//! The exported functions of the module and the three buffers they share with the page: the
//! inbox (the request, written by the page), the outbox (the JSON answer) and the bytes (a
//! render's RGBA). Each lives in a `thread_local` `RefCell` (a WebAssembly instance has one
//! thread); an address is `vec.as_ptr() as usize as u32`, valid until the next call that resizes
//! that buffer.

use crate::ops::call;
use std::cell::RefCell;

thread_local! {
    static INBOX: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    static OUTBOX: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    static BYTES: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
}

/// A buffer's address in the module's memory (a wasm32 address fits u32; elsewhere, where only
/// tests call this, the low bits are enough to tell buffers apart).
#[allow(clippy::cast_possible_truncation)]
fn address(buffer: &[u8]) -> u32 {
    buffer.as_ptr() as usize as u32
}

/// A buffer's length as the page reads it (a wasm32 length fits u32).
fn length(buffer: &[u8]) -> u32 {
    u32::try_from(buffer.len()).unwrap_or(u32::MAX)
}

/// The largest request the inbox takes (64 MiB: a scene with its meshes' OBJ texts).
pub const MAX_REQUEST: u32 = 64 << 20;

/// Reserves `len` bytes (zeroed) for the request and returns their address; the page writes the
/// UTF-8 request JSON there. Above [`MAX_REQUEST`] it reserves nothing and returns 0 (then the
/// call answers that the request is empty), rather than failing to allocate, which would abort.
#[allow(unsafe_code)]
#[no_mangle]
pub extern "C" fn whitted_inbox(len: u32) -> u32 {
    INBOX.with_borrow_mut(|inbox| {
        inbox.clear();
        if len > MAX_REQUEST {
            inbox.shrink_to_fit();
            return 0;
        }
        inbox.resize(len as usize, 0);
        address(inbox)
    })
}

/// Runs the request in the inbox: 0 ok, 2 bad input, 1 anything else (the outbox then holds
/// `{"errors": [...]}`).
#[allow(unsafe_code)]
#[no_mangle]
pub extern "C" fn whitted_call() -> u32 {
    let request = INBOX.with_borrow(Clone::clone);
    let answer = call(&request);
    OUTBOX.with_borrow_mut(|out| *out = answer.json.into_bytes());
    BYTES.with_borrow_mut(|bytes| *bytes = answer.bytes);
    u32::from(answer.code)
}

/// The address of the answer's JSON (UTF-8).
#[allow(unsafe_code)]
#[no_mangle]
pub extern "C" fn whitted_outbox() -> u32 {
    OUTBOX.with_borrow(|b| address(b))
}

/// The answer's length in bytes.
#[allow(unsafe_code)]
#[no_mangle]
pub extern "C" fn whitted_outbox_len() -> u32 {
    OUTBOX.with_borrow(|b| length(b))
}

/// The address of the binary answer (a render's RGBA), empty otherwise.
#[allow(unsafe_code)]
#[no_mangle]
pub extern "C" fn whitted_bytes() -> u32 {
    BYTES.with_borrow(|b| address(b))
}

/// The binary answer's length in bytes.
#[allow(unsafe_code)]
#[no_mangle]
pub extern "C" fn whitted_bytes_len() -> u32 {
    BYTES.with_borrow(|b| length(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exports through their buffers, as the page uses them (natively: the addresses are
    /// not dereferenced here, only the buffers' contents are read back).
    #[test]
    fn a_request_goes_in_and_the_answer_comes_out() {
        let request = br#"{"op": "kinds"}"#;
        whitted_inbox(u32::try_from(request.len()).unwrap());
        INBOX.with_borrow_mut(|inbox| inbox.copy_from_slice(request));
        assert_eq!(whitted_call(), 0);
        let answer = OUTBOX.with_borrow(|b| String::from_utf8(b.clone()).unwrap());
        assert_eq!(whitted_outbox_len() as usize, answer.len());
        assert!(
            answer.starts_with(r#"{"kinds":[{"name":"#) && answer.contains(r#""name":"uv-map""#),
            "{answer}"
        );
        assert_eq!(whitted_bytes_len(), 0);
        whitted_inbox(3);
        INBOX.with_borrow_mut(|inbox| inbox.copy_from_slice(b"{x}"));
        assert_eq!(whitted_call(), 2);
        let answer = OUTBOX.with_borrow(|b| String::from_utf8(b.clone()).unwrap());
        assert!(answer.starts_with(r#"{"errors":["request: "#), "{answer}");
        assert_eq!(whitted_inbox(MAX_REQUEST + 1), 0);
        assert_eq!(whitted_call(), 2);
    }
}
