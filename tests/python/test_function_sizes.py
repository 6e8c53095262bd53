"""scripts/function-sizes.py measures C++ functions as a reader counts them."""
import importlib.util
import pathlib

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "function-sizes.py"
spec = importlib.util.spec_from_file_location("function_sizes", SCRIPT)
function_sizes = importlib.util.module_from_spec(spec)
spec.loader.exec_module(function_sizes)


def body(lines):
    return "\n".join(f"  int v{i} = {i};" for i in range(lines))


def test_functions_methods_and_constructors_with_their_lengths(tmp_path):
    source = tmp_path / "a.cpp"
    source.write_text(
        "namespace x {\n"
        "int short_one(int a) {\n" + body(3) + "\n}\n"
        "Result<std::vector<int>> Foo::long_one(const std::string& s) const noexcept {\n"
        "  auto f = [&](int k) { return k + 1; };\n"
        "  const char* brace = \"{ not a block\";  // } nor here\n"
        "  /* { */ char c = '}';\n" + body(120) + "\n}\n"
        "Foo::Foo(int a) : a_(a), b_(2) {\n" + body(5) + "\n}\n"
        "auto trailing(int a) -> double {\n" + body(2) + "\n}\n"
        "struct S { int m() const { return 1; } };\n"
        "}  // namespace x\n", encoding="utf-8")
    found = {name: lines for name, _, lines in function_sizes.functions_of(source)}
    assert found["short_one"] == 5
    assert found["Foo::long_one"] == 120 + 5
    assert found["Foo::Foo"] == 7
    assert found["trailing"] == 4
    assert found["m"] == 1
    # Control statements and lambdas are not functions of their own.
    assert "if" not in found and "f" not in found


def test_digit_separators_and_raw_strings_do_not_confuse_the_braces(tmp_path):
    source = tmp_path / "b.cpp"
    source.write_text("long big() {\n  long n = 1'000'000;\n  auto r = R\"(}})\";\n  return n;\n}\n"
                      "int after() {\n  return 0;\n}\n", encoding="utf-8")
    found = {name: lines for name, _, lines in function_sizes.functions_of(source)}
    assert found == {"big": 5, "after": 3}
